#include "core/status.h"

namespace conformesh {

namespace {
struct CodeRow {
  Code code;
  const char* name;
  bool fatal;
  const char* meaning;
};
constexpr CodeRow kCodes[] = {
#define CONFORMESH_X(name, value, fatal, text) {Code::name, #name, fatal, text},
    CONFORMESH_STATUS_TABLE(CONFORMESH_X)
#undef CONFORMESH_X
};
constexpr int kCodeCount = int(sizeof(kCodes) / sizeof(kCodes[0]));

const CodeRow* findRow(Code c) {
  for (const CodeRow& r : kCodes)
    if (r.code == c) return &r;
  return nullptr;
}
}  // namespace

const char* codeName(Code c) {
  const CodeRow* r = findRow(c);
  return r ? r->name : "Unknown";
}

const char* codeMeaning(Code c) {
  const CodeRow* r = findRow(c);
  return r ? r->meaning : "unknown status code";
}

bool codeIsFatal(Code c) {
  const CodeRow* r = findRow(c);
  return r ? r->fatal : true;
}

int codeCount() { return kCodeCount; }

Code codeAt(int i) { return (i >= 0 && i < kCodeCount) ? kCodes[i].code : Code::InternalError; }

void fail(Code code, Stage stage, const std::string& message) { throw Error(code, stage, message); }

}  // namespace conformesh
