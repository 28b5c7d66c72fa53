#pragma once
// How libcam writes numbers, in two forms, each in one place:
//   format_number  every digit that matters: the shortest text that reads back to the
//                  same double (files, error messages that quote a value);
//   format_short   a few significant digits, as printf's "%.<digits>g" writes them
//                  (tables, titles and captions meant to be read at a glance).

#include <string>

namespace libcam {

// The shortest representation that round-trips exactly ("0.1", "1e-09", "inf", "-nan").
std::string format_number(double value);

// `significant_digits` significant digits in printf's %g form: "0.000123", "1.23e-09",
// "1e+03", "inf", "nan". Defaults to 3, the precision of libcam's tables and pictures.
std::string format_short(double value, int significant_digits = 3);

}  // namespace libcam
