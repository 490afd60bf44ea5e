// conformesh — Triangle's .poly format (Shewchuk's Triangle documentation, "file formats").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "planar/cdt.h"

namespace conformesh::planar {

//! Parse a .poly file from its bytes into a PSLG. Supported: '#' comments, blank lines,
//! vertex attributes and boundary markers (read and dropped), segment markers (kept in
//! Pslg::segmentMarkers when the header says 1), holes, and 0- or 1-based numbering (taken
//! from the first vertex's number, as Triangle does); an optional regional-attribute section
//! is ignored. Not supported: a vertex count of 0 (vertices in a separate .node file), 3D.
//! Failure: Code::ParseError with the 1-based line number in the message;
//! IndexOutOfRange for segments naming missing vertices; NonFiniteCoordinate.
Pslg readPoly(const std::vector<uint8_t>& bytes);

//! Write a PSLG as a 1-based .poly file (markers written when present).
std::string writePoly(const Pslg& pslg);

}  // namespace conformesh::planar
