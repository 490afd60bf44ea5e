// conformesh — every header of the library, the internal ones too, for the bindings, the CLI and
// the tests. The public API is include/conformesh/conformesh.h.
#pragma once

#include "conformesh/conformesh.h"
#include "conformal/flatten.h"
#include "core/mesh_buffers.h"
#include "core/status.h"
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
