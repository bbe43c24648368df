#include "kinetic/collision/ccd_query_file.h"

#include <cmath>
#include <fstream>
#include <sstream>

// InputError is the project's one way of refusing input; a header of its own, shared by every
// reader (scenes, models, query files).
#include "util/input_error.h"

namespace kinray {
namespace {

mpq_class parse_rational(const std::string& num, const std::string& den, const std::string& where) {
  mpz_class n, d;
  if (n.set_str(num, 10) != 0 || d.set_str(den, 10) != 0)
    throw InputError(where, "expected integers num,den, got '" + num + "," + den + "'");
  if (d == 0) throw InputError(where, "zero denominator");
  mpq_class q(n, d);
  q.canonicalize();
  return q;
}

/// `d` equals the rational `q` exactly. A rational beyond the doubles' range converts to
/// infinity, which has no rational to compare with (GMP stops the process with SIGFPE when asked
/// for one): such a coordinate is simply not a double.
bool is_exactly(double d, const mpq_class& q) { return std::isfinite(d) && mpq_class(d) == q; }

}  // namespace

std::vector<CcdQuery> read_ccd_queries(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the query file");
  std::vector<CcdQuery> queries;
  std::string text;
  int line = 0, row = 0;
  while (std::getline(in, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty()) continue;
    const std::string where = path + ":" + std::to_string(line);
    std::vector<std::string> cells;
    std::stringstream fields(text);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    if (cells.size() != 7)
      throw InputError(where, "expected 7 columns x_num,x_den,y_num,y_den,z_num,z_den,truth, got " +
                                  std::to_string(cells.size()));
    if (cells[6] != "0" && cells[6] != "1")
      throw InputError(where, "truth must be 0 or 1, got '" + cells[6] + "'");
    if (row % 8 == 0) {
      queries.emplace_back();
      queries.back().line = line;
      queries.back().truth = cells[6] == "1";
    } else if ((cells[6] == "1") != queries.back().truth) {
      // Every row of a query repeats its truth value: a row that differs is a corrupt file.
      throw InputError(where, "truth " + cells[6] + " disagrees with the query's first row (line " +
                                  std::to_string(queries.back().line) + ")");
    }
    RationalPoint point;
    for (int k = 0; k < 3; ++k) point[k] = parse_rational(cells[2 * k], cells[2 * k + 1], where);
    CcdQuery& query = queries.back();
    const int index = row % 8;
    (index < 4 ? query.motion.start[index] : query.motion.end[index - 4]) = point;
    ++row;
  }
  if (row % 8 != 0)
    throw InputError(path, std::to_string(row) + " rows, not a multiple of 8 (8 rows per query)");
  if (queries.empty()) throw InputError(path, "no queries");
  for (CcdQuery& query : queries) query.doubles = exactly_as_doubles(query.motion);
  return queries;
}

std::optional<PrimitiveMotion> exactly_as_doubles(const RationalMotion& m) {
  PrimitiveMotion d;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      d.start[i][k] = m.start[i][k].get_d();
      d.end[i][k] = m.end[i][k].get_d();
      if (!is_exactly(d.start[i][k], m.start[i][k]) || !is_exactly(d.end[i][k], m.end[i][k]))
        return std::nullopt;
    }
  return d;
}

}  // namespace kinray
