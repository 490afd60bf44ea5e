// Readable error messages: what went wrong (the library's code, stage and message) and what to do.
import { ConformeshError } from 'conformesh';

const HINTS: Record<string, string> = {
  EmptyMesh: 'The file holds no triangles. Export the surface (not only points or lines) and try again.',
  ParseError:
    'The file could not be read as OBJ, OFF, STL or PLY. Check that it is a complete mesh file (not truncated, the extension matches the content) and re-export it.',
  IndexOutOfRange: 'A face refers to a vertex that does not exist. The file is damaged: re-export it.',
  NonFiniteCoordinate: 'Some vertex coordinates are NaN or infinite. Fix or remove those vertices in the source.',
  DegenerateFace: 'Some faces have zero area. Remove them (merge by distance / clean up) and try again.',
  NonManifoldEdge: 'An edge is shared by more than two triangles. Repair the mesh (split the non-manifold edges or remove the extra faces).',
  NonManifoldVertex: 'Two surface sheets touch at a single vertex. Split that vertex or separate the sheets.',
  InconsistentOrientation: 'The triangles are not consistently oriented. Recompute normals / make the orientation consistent.',
  TooLarge:
    'The file declares more vertices or faces than it holds, or more than the limits allow: it may be truncated (re-export it) or too big for the page (decimate it first, or use the native CLI).',
  InvalidArgument: 'A parameter is out of range. Check the values in the parameter panel.',
  Cancelled: 'The run was cancelled.',
  IterationLimit: 'An iteration cap was hit. Try a larger target edge length, a smaller minimum angle, or a larger feature angle.',
  NotConverged: 'The conformal flow did not converge. Try the "free" boundary condition or a different feature angle.',
  InvalidPslg: 'The planar boundary of a patch is invalid. Try a different feature angle.',
  InvalidTopology: 'The surface topology is not supported here (e.g. a patch could not be cut into a disk). Try a different feature angle.',
  NumericalFailure: 'A numerical step failed. The input may have near-degenerate triangles: clean it up and retry.',
  IoError: 'The WebAssembly module or a file could not be loaded. Reload the page.',
  InternalError: 'This is a bug in conformesh. Please report it with the file that triggers it.',
};

export interface Readable {
  code: string;
  stage: string;
  message: string;
  hint: string;
}

export function readable(e: unknown, context = ''): Readable {
  if (e instanceof ConformeshError || (e && typeof e === 'object' && 'code' in e && 'stage' in e)) {
    const err = e as ConformeshError;
    return {
      code: String(err.code),
      stage: String(err.stage),
      message: context ? `${context}: ${err.message}` : err.message,
      hint: HINTS[String(err.code)] ?? '',
    };
  }
  const message = e instanceof Error ? e.message : String(e);
  return { code: 'Error', stage: 'page', message: context ? `${context}: ${message}` : message, hint: HINTS.InternalError! };
}

export function showError(box: HTMLElement, e: unknown, context = ''): Readable {
  const r = readable(e, context);
  box.replaceChildren();
  const head = document.createElement('div');
  const code = document.createElement('span');
  code.className = 'code';
  code.dataset.testid = 'error-code';
  code.textContent = r.code;
  head.append(code, ` (stage: ${r.stage}) — `, r.message);
  const hint = document.createElement('div');
  hint.className = 'hint';
  hint.textContent = r.hint;
  box.append(head, hint);
  box.hidden = false;
  return r;
}

export function clearError(box: HTMLElement): void {
  box.hidden = true;
  box.replaceChildren();
}
