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
      : std::runtime_error(where.empty() ? what : where + ": " + what), m_where(std::move(where)) {}
  [[nodiscard]] const std::string& where() const { return m_where; }

 private:
  std::string m_where;
};

}  // namespace kinray
