#pragma once
// Temporary files that an interrupt must not leave behind. Every output is written under a
// temporary name and renamed into place (image_io.h, video_writer.h); while it exists the name is
// registered here, and SIGINT, SIGTERM or SIGHUP remove every registered file before the program
// dies of the signal, so Ctrl-C leaves neither a torn output nor a hidden temporary.
#include <string>

namespace kinray {

/// Installs the handlers for SIGINT, SIGTERM and SIGHUP (once; later calls do nothing). The
/// handler unlinks the registered temporaries and re-raises the signal with its default action.
void remove_temporaries_on_interrupt();

/// Registers `path` for as long as the object lives: an interrupt meanwhile removes the file.
/// Registering is lock-free and async-signal-safe to read; up to 64 temporaries at once (more are
/// not registered, which only loses the clean-up).
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::string& path);
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  [[nodiscard]] const std::string& path() const { return m_path; }

 private:
  std::string m_path;
  int m_slot = -1;  ///< index in the registry, -1 when it was full
};

}  // namespace kinray
