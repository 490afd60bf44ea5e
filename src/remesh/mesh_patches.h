// conformesh — many patches meshed on several threads with the result of meshing them one after
// the other: each patch refined apart from the samples as they are (refineApart), then the
// meshings committed in patch order, a meshing whose boundary samples changed in the meantime
// (a patch before it split a segment of their common curve) made again first.
#pragma once

#include <functional>

#include "remesh/mesh_patch.h"

namespace conformesh::pipeline {

//! For k in increasing order, while wanted(todo[k]) (asked at its turn: an earlier meshing can
//! change it), meshPatch(surf, opt, m, todo[k], splitSegments[k]) then meshed(k): the same meshing,
//! samples and stamps whatever opt.threads is. meshed and waiting (while the threads work; may be
//! empty) run on the calling thread only, for progress and cancel. The seconds every refinement
//! and lift took on its thread, a meshing made again included, are added to busy.refine and
//! busy.lift. Fails as meshPatch does, with the error of the first patch in order that fails.
void meshPatches(const Surface& surf, const RemeshOptions& opt, Meshing& m, const std::vector<uint32_t>& todo,
                 const std::vector<uint8_t>& splitSegments, const std::function<bool(uint32_t)>& wanted,
                 const std::function<void(size_t)>& meshed, const std::function<void()>& waiting, StageSeconds& busy);

}  // namespace conformesh::pipeline
