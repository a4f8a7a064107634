// Numbers in messages and text files: one formatting for every library, so an error names a value
// the same way wherever it comes from.
#pragma once

#include <string>

namespace qv {

/// `value` as printf's "%.<significantDigits>g" prints it in the "C" locale: at most
/// `significantDigits` significant digits (clamped to [1, 17]; 17 round-trips any double), no
/// trailing zeros, an exponent only for very large or small magnitudes ("1.5e-07"), the sign of a
/// negative zero kept ("-0"), and "nan", "-nan", "inf" or "-inf" for non-finite values. The decimal
/// point is always '.', whatever locale the process runs in.
std::string formatDouble(double value, int significantDigits = 6);

}  // namespace qv
