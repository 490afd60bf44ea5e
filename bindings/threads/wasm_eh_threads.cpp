// conformesh — C++ exceptions in the threaded WebAssembly module (conformesh-mt), linked with
// -Wl,--wrap=_Unwind_CallPersonality,--wrap=_Unwind_RaiseException,--wrap=__cxa_begin_catch.
//
// clang 14 (Debian's emscripten 3.1.6) writes a landing pad's inputs to __wasm_lpad_context as a
// plain global, while emscripten's libunwind declares it thread_local and hands the personality
// routine its thread's copy: under -pthread no `catch` ever matched (the exception reached JS).
// Here the personality reads the landing pads' copy, the only one the compiled code writes. That
// copy is shared by all threads, so one exception is in flight at a time: a throw takes the lock,
// entering the matching handler releases it (a rethrow or a nested throw on the same thread holds
// it again, counted per thread). A throw on one thread waits while another thread unwinds.
#include <unwind.h>

#include <atomic>
#include <cstdint>

namespace {

struct LandingPadContext {
  uintptr_t lpadIndex;  // written by the landing pad
  uintptr_t lsda;       // written by the landing pad
  uintptr_t selector;   // written by the personality routine
};

std::atomic<bool> inFlight{false};
thread_local int heldByThisThread = 0;

void acquire() {
  if (heldByThisThread++ > 0) return;
  bool expected = false;
  while (!inFlight.compare_exchange_weak(expected, true, std::memory_order_acquire)) expected = false;
}

void release() {
  if (heldByThisThread == 0) return;  // a handler entered without a throw of ours (foreign exception)
  if (--heldByThisThread == 0) inFlight.store(false, std::memory_order_release);
}

}  // namespace

extern "C" {

// Not thread_local on purpose: the address clang 14's landing pads store to.
extern LandingPadContext __wasm_lpad_context;

_Unwind_Reason_Code __gxx_personality_wasm0(int version, _Unwind_Action actions, uint64_t exceptionClass,
                                            _Unwind_Exception* exception, _Unwind_Context* context);
_Unwind_Reason_Code __real__Unwind_RaiseException(_Unwind_Exception* exception);
void* __real___cxa_begin_catch(void* exception) noexcept;

// Called by every landing pad with a catch clause: the personality routine decides the selector.
_Unwind_Reason_Code __wrap__Unwind_CallPersonality(void* exceptionPtr) {
  auto* exception = static_cast<_Unwind_Exception*>(exceptionPtr);
  __wasm_lpad_context.selector = 0;
  // WebAssembly unwinds in one phase: the cleanup phase only
  return __gxx_personality_wasm0(1, _UA_CLEANUP_PHASE, exception->exception_class, exception,
                                 reinterpret_cast<_Unwind_Context*>(&__wasm_lpad_context));
}

// Every throw, rethrow and std::rethrow_exception starts here.
_Unwind_Reason_Code __wrap__Unwind_RaiseException(_Unwind_Exception* exception) {
  acquire();
  return __real__Unwind_RaiseException(exception);
}

// Entering a handler: the landing pads are done with the shared context.
void* __wrap___cxa_begin_catch(void* exception) noexcept {
  void* object = __real___cxa_begin_catch(exception);
  release();
  return object;
}

}  // extern "C"
