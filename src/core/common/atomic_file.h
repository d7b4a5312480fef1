#pragma once
// Writing files so that nothing already written is lost: the new content goes to a
// temporary file in the same folder, is flushed to disk, and only then replaces the
// old file by rename (atomic on POSIX), after which the folder itself is flushed so
// the rename survives a power cut. A failure leaves the old file untouched.
//
// The replaced file keeps its permission bits (a new file gets 0666 less the umask).
// A path that is a symbolic link is written through: its final target is replaced
// and the link stays a link. Temporary files that a killed write left beside the
// file (their writer's process is gone) are removed by the next write.
#include <string>
#include <string_view>

namespace imagepro {

// Returns true on success; on failure `error` names the file and the reason.
// With keep_backup, an existing file is first kept as "<path>.bak", which is replaced
// atomically too (a hard link to the old file, or a copy where links cannot be made).
bool writeFileAtomically(const std::string& path, std::string_view content, std::string& error,
                         bool keep_backup = false);

// Reads a whole file; false with `error` naming the file and the reason.
bool readWholeFile(const std::string& path, std::string& content, std::string& error);

// The temporary file name a write of `path` by process `pid` starts with (the name
// ends in random characters): ".<file name>.tmp-<pid>-". Exposed for the tests.
std::string atomicTemporaryPrefix(const std::string& file_name, long pid);

}  // namespace imagepro
