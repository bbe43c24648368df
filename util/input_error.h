#pragma once
// Bad input (scene files, models, flags) throws InputError, carrying where it came from; it is
// caught once, in main, which prints one line and exits non-zero (Mitsuba's Throw, pbrt's FileLoc).
#include <stdexcept>
#include <string>

namespace kinray {

class InputError : public std::runtime_error {
 public:
  /// `where` names the file (and key or line) at fault; `what` says the problem.
  InputError(std::string where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what),
        m_where(std::move(where)),
        m_message(what) {}
  [[nodiscard]] const std::string& where() const { return m_where; }
  /// The problem alone, without where().
  [[nodiscard]] const std::string& message() const { return m_message; }

 private:
  std::string m_where;
  std::string m_message;
};

/// A bad option value given to the library, named by its field in the config struct
/// ("embree_packet" of BackendConfig), not by a command-line flag: the library knows no flags.
/// The command line turns the field into its flag (tools/cli_errors.h, name_the_flag).
class OptionError : public InputError {
 public:
  OptionError(std::string field, const std::string& what) : InputError(std::move(field), what) {}
};

}  // namespace kinray
