#pragma once
// Writing files so that nothing already written is lost: the new content goes to a
// temporary file in the same folder, is flushed to disk, and only then replaces the
// old file by rename (atomic on POSIX). A failure leaves the old file untouched.
#include <string>
#include <string_view>

namespace imagepro {

// Returns true on success; on failure `error` names the file and the reason.
// With keep_backup, an existing file is first copied to "<path>.bak".
bool writeFileAtomically(const std::string& path, std::string_view content, std::string& error,
                         bool keep_backup = false);

// Reads a whole file; false with `error` naming the file and the reason.
bool readWholeFile(const std::string& path, std::string& content, std::string& error);

}  // namespace imagepro
