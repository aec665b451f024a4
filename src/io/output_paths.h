// Private to src/io: what stands in the way of writing a file, shared by the
// checks made before a run (check_output_path) and the writers' messages.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace pdd::io {

// The folder a file `path` goes into ("." for a bare name).
std::filesystem::path folder_of(const std::string& path);

// The longest file name `folder`'s file system accepts (NAME_MAX when unknown).
std::size_t name_max(const std::filesystem::path& folder);

// Why the file `path` cannot be created or replaced, or "" when it can: its
// folder is missing, not a folder or not writable, it is itself a folder or
// not a regular file, or its name is too long.
std::string target_problem(const std::string& path);

}  // namespace pdd::io
