// conformesh — the flat mesh arrays: public, in include/conformesh/buffers.h.
#pragma once

#include "conformesh/buffers.h"
