#include "core/stages.h"

namespace conformesh {
namespace {

struct StageRow {
  const char* name;
  const char* key;
  const char* label;
  int weight;
};
constexpr StageRow kStages[] = {
#define CONFORMESH_X(id, key, name, label, weight) {name, #key, label, weight},
    CONFORMESH_STAGE_TABLE(CONFORMESH_X)
#undef CONFORMESH_X
};
constexpr int kStageCount = int(sizeof(kStages) / sizeof(kStages[0]));

// what the lookups answer for a value outside the table
constexpr StageRow kUnknown{"unknown", "unknown", "unknown", 0};

const StageRow& row(Stage s) {
  const int i = int(s);
  return i >= 0 && i < kStageCount ? kStages[i] : kUnknown;
}

}  // namespace

int stageCount() { return kStageCount; }

bool isRemeshStage(Stage s) {
  for (Stage r : kRemeshStages)
    if (r == s) return true;
  return false;
}

const char* stageName(Stage s) { return row(s).name; }
const char* stageKey(Stage s) { return row(s).key; }
const char* stageLabel(Stage s) { return row(s).label; }
int stageWeight(Stage s) { return row(s).weight; }

StageInterval progressInterval(Stage s) {
  // integer sums, so the TypeScript table gets the same doubles with the same two divisions
  int before = 0, total = 0;
  for (int i = 0; i < kStageCount; ++i) {
    if (i < int(s)) before += kStages[i].weight;
    total += kStages[i].weight;
  }
  const int own = stageWeight(s);
  return StageInterval{double(before) / double(total), double(before + own) / double(total)};
}

}  // namespace conformesh
