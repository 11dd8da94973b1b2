// The files an input opens (issue 39 item 8): fuzz/open_watch.cpp replaces the C library's
// open functions in a fuzz executable and calls note_open with each path; the target defines
// note_open (fuzz/fuzz_urdf.cpp records the paths while it builds a scene and checks that
// every one is inside the input's scratch directory). Declarations only: open_watch.cpp must
// not see the C library's declarations of the functions it defines.
#pragma once

namespace stiction::fuzz {

inline constexpr int kCurrentDirectory = -100;  // AT_FDCWD on Linux

// A path passed to open/openat/fopen; `dir` is openat's directory descriptor.
void note_open(const char* path, int dir = kCurrentDirectory);

}  // namespace stiction::fuzz
