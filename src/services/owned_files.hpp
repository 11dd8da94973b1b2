// The files a command of this program may call its own, and how it removes them: by name
// pattern (temporaries of a killed run, plots, frames), by a manifest (an output directory's
// .stiction-output), never following a symlink, never leaving a given directory.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace stiction::services {

// A relative path that stays inside its directory: not empty, not absolute, no "." or ".."
// part (what a manifest or a golden.json written by anyone may name).
bool is_inside(const std::filesystem::path& relative);

// ".NAME.tmp-<hex>" (sys/temporaries.hpp) or an older "NAME.tmp.<n>".
bool is_temporary_name(const std::string& name);
bool is_frame_name(const std::string& name);  // NNNNNN.png
bool is_plot_name(const std::string& name);   // *.png, *.svg, *.pdf

// Removes the temporaries directly in `dir` whose names `is_temporary_name` accepts and that
// begin with one of `prefixes` (".NAME.tmp-" of a file this command writes; empty: any).
void remove_temporaries(const std::filesystem::path& dir,
                        const std::vector<std::string>& prefixes = {});

// Removes `path` when it is a file or a link (the link itself, never its target); never a
// directory.
void remove_owned_file(const std::filesystem::path& path);

// Creates the directories `relative` (inside `dir`) names, refusing to pass through a link
// or a non-directory (io::IoError): nothing is ever written through a link.
void make_real_directories(const std::filesystem::path& dir, const std::filesystem::path& relative);

// DIR/.stiction-output's files (or, for a directory of an older stiction, summary.json's
// `files`), each inside DIR; nullopt when there is neither.
std::optional<std::vector<std::string>> read_output_manifest(const std::filesystem::path& dir);
// Writes DIR/.stiction-output atomically: {"stiction_output": 1, "files": [...]}.
void write_output_manifest(const std::filesystem::path& dir, const std::vector<std::string>& files);

// Regular file (true) or absent (false): scene::InputError (exit 2) naming `path` when it is a FIFO, a device, a socket
// or a directory (opening one could block for ever or read without end).
bool regular_file_or_absent(const std::filesystem::path& path);

}  // namespace stiction::services
