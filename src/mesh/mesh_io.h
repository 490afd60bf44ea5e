// conformesh — mesh readers and writers: public, in include/conformesh/mesh_io.h.
#pragma once

#include "conformesh/mesh_io.h"
