// conformesh — the stage table: public, in include/conformesh/stages.h.
#pragma once

#include "conformesh/stages.h"
