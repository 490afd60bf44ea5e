// The status table as seen from JavaScript. The single definition is the C++ table
// (include/conformesh/status.h); this copy exists only so the TypeScript union of codes can be a type, and
// tests/js/status.test.ts checks it row by row against the module's statusTable() export.
import { isStageName, type StageName } from './stages.js';
import type { Refine2dResult, RemeshResult } from './types.js';

/** Every status code by name, with its numeric value (same values as C++ `conformesh::Code`). */
export const StatusCode = {
  Ok: 0,
  EmptyMesh: 1,
  ParseError: 2,
  IndexOutOfRange: 3,
  NonFiniteCoordinate: 4,
  DegenerateFace: 5,
  NonManifoldEdge: 6,
  NonManifoldVertex: 7,
  InconsistentOrientation: 8,
  TooLarge: 9,
  InvalidArgument: 10,
  Cancelled: 11,
  IterationLimit: 12,
  NotConverged: 13,
  InvalidPslg: 14,
  InvalidTopology: 15,
  NumericalFailure: 16,
  IoError: 17,
  InternalError: 18,
} as const;

/** Name of a status code, e.g. `'ParseError'`. */
export type StatusCodeName = keyof typeof StatusCode;
/** Codes a ConformeshError can carry (every code but `Ok`). */
export type ErrorCode = Exclude<StatusCodeName, 'Ok'>;

/** Structured form of a ConformeshError, safe to post between threads (`result` holds typed arrays). */
export interface ConformeshErrorData {
  code: ErrorCode;
  value: number;
  stage: StageName;
  message: string;
  result?: RemeshResult | Refine2dResult;
}

/**
 * The one error type of the package: every status but Ok throws it. `code` is the status-table
 * name (`'ParseError'`, ...), `value` its number, `stage` the pipeline stage it arose in; `message`
 * says what and where. `result`: the partial result, when there is one: the defective output of a
 * remesh that failed its topology check, when the call asked for it
 * (RemeshOptions.keepDefectiveOutput), or the valid mesh of a refine2d stopped at maxInsertions
 * (IterationLimit); otherwise undefined.
 */
export class ConformeshError extends Error {
  readonly code: ErrorCode;
  readonly value: number;
  readonly stage: StageName;
  readonly result?: RemeshResult | Refine2dResult;

  constructor(code: ErrorCode, stage: StageName, message: string, result?: RemeshResult | Refine2dResult) {
    super(message);
    this.name = 'ConformeshError';
    this.code = code;
    this.value = StatusCode[code];
    this.stage = stage;
    if (result !== undefined) this.result = result;
  }

  /** Plain data (for postMessage and JSON). */
  toJSON(): ConformeshErrorData {
    return { code: this.code, value: this.value, stage: this.stage, message: this.message };
  }

  /** Rebuild from toJSON() data, with `result` when given (e.g. received from a worker). Unknown codes become InternalError. */
  static fromData(data: Partial<ConformeshErrorData>): ConformeshError {
    const code = isErrorCode(data.code) ? data.code : 'InternalError';
    const stage = isStageName(data.stage) ? data.stage : 'api';
    return new ConformeshError(code, stage, String(data.message ?? 'unknown error'), data.result);
  }
}

export function isErrorCode(x: unknown): x is ErrorCode {
  return typeof x === 'string' && x !== 'Ok' && Object.prototype.hasOwnProperty.call(StatusCode, x);
}

/** Shorthand for argument errors detected in the facade. */
export function invalidArgument(message: string, stage: StageName = 'api'): ConformeshError {
  return new ConformeshError('InvalidArgument', stage, message);
}
