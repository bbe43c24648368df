// The CCD query-file reader (kinetic/collision/ccd_query_file.h) on arbitrary text, then each of
// the first queries through the primitive CCD of both kinds: the floating-point path (filters, then
// exact) when the coordinates are doubles, and the exact rational test, which must agree on
// whether the pair collides (both are exact decisions; a disagreement is a finding).
//
// Coordinates of more than 128 bits (numerator or denominator) are read but not run: the exact
// test's cost grows with their size, which would only report the fuzzer's own time limit.
#include <stdexcept>

#include "kinetic/collision/ccd_query_file.h"
#include "kinetic/collision/primitive_ccd.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

bool small_enough(const kinray::RationalMotion& motion) {
  for (const auto* points : {&motion.start, &motion.end})
    for (const kinray::RationalPoint& p : *points)
      for (const mpq_class& q : p)
        if (mpz_sizeinbase(q.get_num_mpz_t(), 2) > 128 || mpz_sizeinbase(q.get_den_mpz_t(), 2) > 128)
          return false;
  return true;
}

}  // namespace

KINRAY_FUZZ_TARGET(ccd_queries) {
  const std::string path = kinray::fuzz::write_scratch_file("queries.csv", bytes);
  const std::vector<kinray::CcdQuery> queries = kinray::read_ccd_queries(path);
  for (std::size_t i = 0; i < queries.size() && i < 4; ++i) {
    const kinray::CcdQuery& query = queries[i];
    if (!small_enough(query.motion)) continue;
    const std::optional<kinray::PrimitiveMotion>& doubles = query.doubles;
    for (const kinray::ContactType type :
         {kinray::ContactType::vertex_face, kinray::ContactType::edge_edge}) {
      const bool exact_hit = !kinray::exact_contact_times(type, query.motion).empty();
      if (doubles && exact_hit != !kinray::contact_times(type, *doubles).empty())
        throw std::logic_error("ccd_queries: the floating-point path and the exact test disagree");
    }
  }
}
