#pragma once
// The query files of the CCD benchmark of Wang et al. (2021) (the format of
// ../shared/data/ccd/README.md): 8 rows of rational coordinates x_num,x_den,y_num,y_den,z_num,z_den
// and the exact ground truth per query. Read by `kinray ccd-queries` and fuzzed
// (tests/fuzz/targets/ccd_queries.cpp): a malformed file is an InputError naming the file and line.
#include <optional>
#include <string>
#include <vector>

#include "kinetic/collision/contact_pair.h"
#include "kinetic/collision/exact_ccd.h"

namespace kinray {

/// One query: the primitive pair's motion, exact, and whether the pair truly collides.
struct CcdQuery {
  RationalMotion motion;
  /// The motion in doubles when every coordinate is exactly one (exactly_as_doubles), converted
  /// and checked once when the file is read, so that a timed run of the queries pays neither.
  std::optional<PrimitiveMotion> doubles;
  bool truth = false;
  int line = 0;  ///< first line of the query in the file
};

/// Every query of the file at `path`, in file order; throws InputError on a malformed file.
[[nodiscard]] std::vector<CcdQuery> read_ccd_queries(const std::string& path);

/// The motion in doubles when every coordinate is exactly a (finite) double, so that it can take
/// the floating-point filters as meshes do; std::nullopt otherwise (then only the exact test).
[[nodiscard]] std::optional<PrimitiveMotion> exactly_as_doubles(const RationalMotion& motion);

}  // namespace kinray
