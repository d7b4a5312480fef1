// Checks of a caller's preconditions, where a mistake would otherwise corrupt memory
// quietly (a buffer of the wrong size, an index past the end). They run in debug
// builds (no NDEBUG) and in the sanitizer builds, and compile to nothing in release
// builds, so the frame loop pays nothing for them.
//
//   IMAGEPRO_EXPECTS(grey.size() == width * height, "grey image matches its size");
//
// A failed check prints the condition, the message and where it is, then aborts.
#pragma once

namespace imagepro::detail {

[[noreturn]] void contractFailed(const char* condition, const char* message, const char* file, int line);

}  // namespace imagepro::detail

#if defined(NDEBUG) && !defined(IMAGEPRO_CONTRACTS)
#define IMAGEPRO_EXPECTS(condition, message) static_cast<void>(0)
#else
#define IMAGEPRO_EXPECTS(condition, message)                                                     \
  (static_cast<bool>(condition)                                                                  \
       ? static_cast<void>(0)                                                                    \
       : ::imagepro::detail::contractFailed(#condition, message, __FILE__, __LINE__))
#endif
