// SPDX-License-Identifier: BSD-3-Clause
// stickslip/detail/atomic_file.hpp -- files that are written whole or not at
// all: the command's --output and the checkpoints share this one writer.
//
// Why: a result or a checkpoint rewritten in place is, after a kill, a full
// disk or a crash, part old and part new, and a run killed halfway leaves a
// file that looks finished. So the text goes to a temporary in the target's
// own directory (a rename is atomic only within one file system), is synced,
// and is renamed over the target: a reader sees the old file or the new one.
//
// The temporary is unnamed where the kernel and file system allow it
// (O_TMPFILE): a process killed by SIGKILL, which no handler sees, then
// leaves nothing behind, because an unnamed file dies with its last
// descriptor. It gets a name only at commit, for the instant between linkat()
// and rename(). Elsewhere (old kernels, some network file systems) the
// temporary is named from the start. Either name is
// `<target>.tmp.<host>.<pid>.<n>`, so that a later write to the same target
// can recognise, and remove, the temporaries of processes of this host that
// no longer exist; a live process's, or another host's (a shared file system
// under MPI), is never touched. A signal handler of the caller can remove the
// temporaries in flight (remove_temporaries() is async-signal-safe); the
// library installs no handler of its own.
//
// Symbolic links are followed by hand (resolve_target): a link stays a link
// and its target is what gets replaced, also when the target does not exist
// yet. A replaced file keeps its mode and, where permitted, its owner.
#pragma once

/// \file
/// The atomic-file writer shared by --output and checkpoints (an internal
/// interface, not part of the library's stable API). The comment at the top of
/// this header explains the design.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace stickslip::detail {

/// What a path names, symbolic links followed.
struct FileTarget {
    enum class Kind {
        missing,          ///< nothing there yet: a file would be created at `path`
        regular,          ///< a regular file
        directory,        ///< a directory
        character_device, ///< /dev/null, a terminal...
        block_device,     ///< a disk
        fifo,             ///< a named pipe
        socket,           ///< a socket file
        descriptor,       ///< /dev/stdout, /dev/fd/N...: this process's `descriptor`
    };
    Kind kind = Kind::missing;
    /// The object itself (the end of a chain of links), or where a missing
    /// file is to be created; empty for Kind::descriptor.
    std::string path;
    int descriptor = -1;      ///< Kind::descriptor: the descriptor the path stands for
    int error = 0;            ///< errno when the path cannot be resolved (then nothing else holds)
    std::uint64_t device = 0; ///< st_dev of an existing object
    std::uint64_t inode = 0;  ///< st_ino of an existing object
    std::uint64_t size = 0;   ///< st_size of an existing object

    bool exists() const { return kind != Kind::missing && kind != Kind::descriptor; }
};

/// Resolves `path` as a writer must: a chain of links is followed by hand
/// (not realpath(), which fails on a link to a file that does not exist yet);
/// a relative link target is taken from the link's own directory; /dev/stdout,
/// /dev/fd/N and /proc/self/fd/N are this process's descriptors. Never throws;
/// a path that cannot be resolved (a loop, a directory that cannot be read)
/// has `error` set.
FileTarget resolve_target(const std::string& path);

/// "a directory", "a FIFO", "a character device"...: for messages.
const char* describe(FileTarget::Kind kind);

/// True when `a` and `b` (both resolved, without error) are the same file:
/// the same device and inode when both exist, else the same location once
/// their directories are made canonical. Two descriptors are the same when
/// their numbers are.
bool same_file(const FileTarget& a, const FileTarget& b);

/// A file replaced whole or not at all. Not thread-safe; one object per
/// write. Errors are thrown as std::system_error whose code() is the errno;
/// its what() names the target.
class AtomicFile {
public:
    /// How the temporary is made (a test forces the fallback with `named`).
    enum class Temporary { unnamed_if_possible, named };

    /// Opens the temporary for replacing `target`, which is a resolved path
    /// (resolve_target: a regular file or none, not a link) whose directory
    /// must exist and be writable. First removes the stale temporaries of
    /// `target` left by dead processes of this host.
    explicit AtomicFile(std::string target, Temporary how = Temporary::unnamed_if_possible);
    /// Discards the temporary unless committed.
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    /// Appends `text` to the temporary.
    void write(std::string_view text);
    /// Gives the temporary the mode and owner of the file it replaces (a new
    /// file: 0666 less the umask), syncs it, renames it over the target and
    /// syncs the directory. After a failure the target is unchanged and the
    /// temporary gone.
    void commit();
    /// Closes and removes the temporary; the target is unchanged.
    void discard() noexcept;

    /// True while the temporary has no name (O_TMPFILE).
    bool unnamed() const;
    /// The temporary's name while it has one, else "".
    const std::string& temporary_name() const;
    /// The target.
    const std::string& target() const;

private:
    struct State;
    std::unique_ptr<State> s_;
};

/// Replaces `target` (resolved, see AtomicFile) by `text`, atomically.
void write_file_atomically(const std::string& target, std::string_view text);

/// The prefix of the names of this host's temporaries for `target`
/// (`<target>.tmp.<host>.`, the file name shortened to fit): a name is this
/// prefix followed by `<pid>.<n>`.
std::string temporary_prefix(const std::string& target);

/// Removes every named temporary of this process that is in flight. Only
/// async-signal-safe calls: for a handler of a signal about to end the
/// process.
void remove_temporaries() noexcept;

} // namespace stickslip::detail
