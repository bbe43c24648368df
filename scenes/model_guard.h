#pragma once
// assimp 5.2 crashes (SIGSEGV) on some malformed files, e.g. DirectX .x skin weights that index
// past the mesh's vertices, and a hostile file may make a loader loop or allocate without end.
// No try/catch survives that, so the importer first lets a forked child process read the file:
// only when the child finishes cleanly does the importer read it itself (assimp is
// deterministic), and a crash or a hang becomes an InputError instead of taking kinray down.
#include <functional>
#include <optional>
#include <string>

namespace kinray {

/// Runs `work` in a child process (fork), with the child's stdout sent to stderr and, when
/// `address_space_bytes` > 0, its address space limited to that (so that a file that makes a
/// loader allocate without end fails at once with bad_alloc instead of filling memory). Returns
/// nothing when `work` returned an empty string, and otherwise why not: the text it returned, the
/// signal that killed it, or that it ran longer than `timeout_seconds` (it is then killed). When
/// no child can be started, runs nothing and returns nothing: the caller's own attempt decides.
/// The fork waits until no thread of the project's own is working (util/fork_gate.h); `work`
/// must not start threads (the child has only the one that forked).
[[nodiscard]] std::optional<std::string> run_in_child(const std::function<std::string()>& work,
                                                      double timeout_seconds,
                                                      size_t address_space_bytes = 0);

/// The address space a reading child gets: what this process already uses plus half of the
/// machine's physical memory, at most 8 GiB (a model whose reading needs more is refused).
[[nodiscard]] size_t reader_address_space();

/// While alive, sends whatever is written to stdout (file descriptor 1) to stderr instead: a few
/// assimp loaders print with printf (e.g. OpenGEX's "nullptr returned by creating DDLNode."), and
/// stdout belongs to the tools' output.
class StdoutToStderr {
 public:
  StdoutToStderr();
  ~StdoutToStderr();
  StdoutToStderr(const StdoutToStderr&) = delete;
  StdoutToStderr& operator=(const StdoutToStderr&) = delete;

 private:
  int m_saved = -1;
};

}  // namespace kinray
