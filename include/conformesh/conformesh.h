// conformesh — the public C++ API: flat mesh buffers, the status codes and stages, reading and
// writing mesh files, and remesh() with its options and report. No internal header and no Eigen:
// a program needs only include/ and the library (libconformesh.a).
//
// Surface remeshing by discrete conformal maps: split along features, flatten each patch by
// discrete Ricci flow with intrinsic Delaunay flips, refine in the plane (Delaunay refinement),
// lift back to the input surface and stitch. See docs/ARCHITECTURE.md.
#pragma once

#define CONFORMESH_VERSION "0.1.0"

#include "conformesh/buffers.h"
#include "conformesh/mesh_io.h"
#include "conformesh/remesh.h"
#include "conformesh/stages.h"
#include "conformesh/status.h"
