// conformesh — the one public C++ header.
//
// Surface remeshing by discrete conformal maps: split along features, flatten each patch by
// discrete Ricci flow with intrinsic Delaunay flips, refine in the plane (Delaunay refinement),
// lift back to the input surface and stitch. See docs/ARCHITECTURE.md.
#pragma once

#define CONFORMESH_VERSION "0.1.0"

#include "core/mesh_buffers.h"
#include "core/status.h"
#include "conformal/flatten.h"
#include "mesh/halfedge_mesh.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_io.h"
#include "mesh/primitives.h"
#include "mesh/topology.h"
#include "mesh/validate.h"
#include "mesh/weld_vertices.h"
#include "planar/cdt.h"
#include "planar/poly_io.h"
#include "planar/refine.h"
#include "remesh/remesh.h"
