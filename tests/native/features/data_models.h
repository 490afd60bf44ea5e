// The models of ../shared/data for the features tests, and the feature options the remesh gives them.
#pragma once

#include <doctest/doctest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/mesh_buffers.h"
#include "features/edge_graph.h"
#include "features/segmentation.h"
#include "features/sizing.h"
#include "mesh/mesh_io.h"

namespace conformesh::testshapes {

//! The model `name` of ../shared/data (its file name tells the reader the format).
inline MeshBuffers dataModel(const std::string& name) {
  std::ifstream in(std::string(CONFORMESH_DATA_DIR) + "/" + name, std::ios::binary);
  REQUIRE(in);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ReadOptions ro;
  ro.fileName = name;
  return readMesh(bytes, ro).mesh;
}

//! The feature options the remesh sets at its default target (0.01 of the diagonal) and
//! minimum edge length (a tenth of it): src/remesh/prepare.cpp.
inline features::FeatureOptions remeshFeatureOptions(const features::EdgeGraph& g) {
  const double target = 0.01 * features::boundingBoxDiagonal(g);
  features::FeatureOptions fo;
  fo.junctionScale = target;
  fo.minFeatureLength = 2 * target;
  fo.minPatchWidth = 0.05 * target;
  return fo;
}

}  // namespace conformesh::testshapes
