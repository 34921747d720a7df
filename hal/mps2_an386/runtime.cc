// The C and C++ run-time support of the image, without a heap: the firmware allocates nothing (fixed
// pools, static storage), so operator new and delete only trap, and newlib's malloc is never linked in.
// There is deliberately no _sbrk: an image that pulls malloc in (directly, or through a stdio function
// that allocates) fails to link, and the board.no_heap test checks the built image for the symbols.
//
// What the libraries would do on an error they cannot return (a C++ library check that would throw,
// abort()) ends here too, in Panic(): newlib's abort() raises a signal, and its signal table is
// allocated; libstdc++'s __throw_* functions call that abort().
#include <cstddef>
#include <cstdlib>
#include <new>
#include <stdexcept>

#include "panic.h"

namespace {

[[noreturn]] void LibraryError(const char* what) {
  hal::TextLine line;
  line.Text("fault: C++ library error (").Text(what).Text(")");
  hal::mps2::Panic(line.view());
}

}  // namespace

void* operator new(std::size_t) { hal::mps2::Panic("fault: operator new called (the firmware has no heap)"); }
void* operator new[](std::size_t) { hal::mps2::Panic("fault: operator new[] called (the firmware has no heap)"); }
void* operator new(std::size_t, const std::nothrow_t&) noexcept { return nullptr; }
void* operator new[](std::size_t, const std::nothrow_t&) noexcept { return nullptr; }

// Referenced by the deleting destructors of classes with virtual destructors; never called, since no
// object of the firmware lives on a heap.
void operator delete(void*) noexcept { hal::mps2::Panic("fault: operator delete called (the firmware has no heap)"); }
void operator delete(void*, std::size_t) noexcept {
  hal::mps2::Panic("fault: operator delete called (the firmware has no heap)");
}
void operator delete[](void*) noexcept { hal::mps2::Panic("fault: operator delete[] called (the firmware has no heap)"); }
void operator delete[](void*, std::size_t) noexcept {
  hal::mps2::Panic("fault: operator delete[] called (the firmware has no heap)");
}

// libstdc++'s checks (std::string_view::substr past the end, std::array::at ...): with exceptions off
// they have nowhere to go.
namespace std {
void __throw_bad_exception() { LibraryError("bad_exception"); }
void __throw_bad_alloc() { LibraryError("bad_alloc"); }
void __throw_bad_array_new_length() { LibraryError("bad_array_new_length"); }
void __throw_bad_cast() { LibraryError("bad_cast"); }
void __throw_bad_typeid() { LibraryError("bad_typeid"); }
void __throw_logic_error(const char*) { LibraryError("logic_error"); }
void __throw_domain_error(const char*) { LibraryError("domain_error"); }
void __throw_invalid_argument(const char*) { LibraryError("invalid_argument"); }
void __throw_length_error(const char*) { LibraryError("length_error"); }
void __throw_out_of_range(const char*) { LibraryError("out_of_range"); }
void __throw_out_of_range_fmt(const char*, ...) { LibraryError("out_of_range"); }
void __throw_runtime_error(const char*) { LibraryError("runtime_error"); }
void __throw_range_error(const char*) { LibraryError("range_error"); }
void __throw_overflow_error(const char*) { LibraryError("overflow_error"); }
void __throw_underflow_error(const char*) { LibraryError("underflow_error"); }
}  // namespace std

extern "C" {

void abort() { hal::mps2::Panic("fault: abort() called"); }

// A pure virtual function called through a half-built or destroyed object.
void __cxa_pure_virtual() { hal::mps2::Panic("fault: pure virtual function called"); }

// The card never exits, so destructors of static objects never run: nothing to register (and newlib's
// registration table, which may allocate, stays out of the image).
int __cxa_atexit(void (*)(void*), void*, void*) { return 0; }
int __aeabi_atexit(void*, void (*)(void*), void*) { return 0; }
void* __dso_handle = nullptr;

}  // extern "C"
