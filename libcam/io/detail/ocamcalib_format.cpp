#include "libcam/io/detail/ocamcalib_format.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <numbers>

#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/ocamcalib.hpp"
#include "libcam/lens/ocamcalib.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

constexpr int kPolynomialTerms = OcamCalibLens<double>::kDegree + 1;  // a0..a5

// The toolbox's five sections, in its order, as messages name them.
constexpr std::array<std::string_view, 5> kSections = {
    "the DIRECT mapping polynomial (pol: count, a0, a1, ...)",
    "the inverse mapping polynomial (invpol: count, b0, b1, ...)",
    "the centre (row, column)",
    "the affine parameters (c, d, e)",
    "the image size (height, width)",
};

struct NumberLine {
    int line = 0;
    std::vector<double> values;
};

[[noreturn]] void fail_at(const std::string& source, int line, std::string_view section, const std::string& what) {
    throw FileError(source + ": line " + std::to_string(line) + ": " + std::string(section) + ": " + what);
}

// Every line that is neither blank nor a # comment, as numbers.
std::vector<NumberLine> number_lines(std::string_view text, const std::string& source) {
    std::vector<NumberLine> lines;
    std::size_t at = 0;
    int number = 0;
    while (at < text.size()) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::string_view line = text.substr(at, end - at);
        at = end + 1;
        ++number;
        const auto start = line.find_first_not_of(" \t\r");
        if (start == std::string_view::npos || line[start] == '#') continue;
        const std::string_view section = lines.size() < kSections.size() ? kSections[lines.size()] : "after the image size";
        if (lines.size() == kSections.size()) {
            fail_at(source, number, section, "unexpected line " + shown_value(line.substr(start)));
        }
        NumberLine parsed{number, {}};
        std::string_view rest = line.substr(start);
        while (true) {
            const auto word = rest.find_first_not_of(" \t\r");
            if (word == std::string_view::npos) break;
            rest = rest.substr(word);
            const std::string_view token = rest.substr(0, rest.find_first_of(" \t\r"));
            double value = 0.0;
            const auto [stop, error] = std::from_chars(token.data(), token.data() + token.size(), value);
            if (error != std::errc() || stop != token.data() + token.size() || !std::isfinite(value)) {
                fail_at(source, number, section, "expected a number, got " + shown_value(token));
            }
            parsed.values.push_back(value);
            rest = rest.substr(token.size());
        }
        lines.push_back(std::move(parsed));
    }
    if (lines.size() < kSections.size()) {
        throw FileError(source + ": " + std::string(kSections[lines.size()]) + ": missing (the file ends at line " +
                        std::to_string(number) + ")");
    }
    return lines;
}

// A "count c0 c1 ..." line's coefficients, the count checked against them.
std::vector<double> counted(const NumberLine& line, std::string_view section, const std::string& source) {
    const double count = line.values.front();
    const std::size_t given = line.values.size() - 1;
    if (!(count == static_cast<double>(given)) || given == 0) {
        fail_at(source, line.line, section,
                "the count " + format_number(count) + " does not match the " + std::to_string(given) + " numbers after it");
    }
    return {line.values.begin() + 1, line.values.end()};
}

void expect_count(const NumberLine& line, std::size_t count, std::string_view section, const std::string& source) {
    if (line.values.size() != count) {
        fail_at(source, line.line, section, "expected " + std::to_string(count) + " numbers, got " +
                                                std::to_string(line.values.size()));
    }
}

// The camera of a forward polynomial P (the ray's component along the optical axis as a
// polynomial of the sensor radius, P(0) > 0, lowest degree first), the affine [1 e; d c]
// acting on (x, y) sensor coordinates, the centre and the size: fx = fy = P(0), k_i =
// P_i P(0)^(i - 1). `where` names the file and the polynomial's place for messages.
Camera ocamcalib_camera(std::span<const double> forward, std::array<double, 3> cde, Vec2 centre, ImageSize size,
                        const std::string& where) {
    if (!(forward[0] > 0.0)) throw FileError(where + ": a0 must look along the optical axis, got " + format_number(forward[0]));
    if (forward.size() > static_cast<std::size_t>(kPolynomialTerms)) {
        throw NotRepresentable(where + ": " + std::to_string(forward.size()) +
                               " coefficients: libcam's OCAMCALIB holds polynomials up to degree " +
                               std::to_string(kPolynomialTerms - 1));
    }
    const double f = forward[0];
    Camera camera;
    camera.size = size;
    camera.intrinsics = {f, f, centre.x(), centre.y(), 0.0};
    camera.lens = {LensType::OcamCalib, {cde[0], cde[1], cde[2]}};
    double power = 1.0;
    for (std::size_t i = 1; i < static_cast<std::size_t>(kPolynomialTerms); ++i) {
        camera.lens.coefficients.push_back(i < forward.size() ? forward[i] * power + 0.0 : 0.0);  // + 0: no -0
        power *= f;
    }
    return validated_camera(std::move(camera), where);
}

struct ToolboxFile {
    Camera camera;
    OcamCalibInverse inverse;
};

ToolboxFile parse_toolbox(std::string_view text, const std::string& source) {
    const std::vector<NumberLine> lines = number_lines(text, source);
    const std::vector<double> pol = counted(lines[0], kSections[0], source);
    std::vector<double> invpol = counted(lines[1], kSections[1], source);
    expect_count(lines[2], 2, kSections[2], source);
    expect_count(lines[3], 3, kSections[3], source);
    expect_count(lines[4], 2, kSections[4], source);
    const auto side = [&](double value) {
        if (!(value >= 1 && value <= static_cast<double>(kMaxImageSide) && value == std::floor(value))) {
            fail_at(source, lines[4].line, kSections[4], "expected whole numbers in [1, " + std::to_string(kMaxImageSide) +
                                                             "], got " + format_number(value));
        }
        return static_cast<long>(value);
    };
    const ImageSize size{side(lines[4].values[1]), side(lines[4].values[0])};
    // The toolbox's z looks backwards (a0 < 0): libcam's forward polynomial is -pol.
    std::vector<double> forward(pol.size());
    std::transform(pol.begin(), pol.end(), forward.begin(), [](double a) { return -a; });
    const std::string where = source + ": line " + std::to_string(lines[0].line) + ": " + std::string(kSections[0]);
    const Vec2 centre(lines[2].values[1], lines[2].values[0]);  // (column, row)
    Camera camera = ocamcalib_camera(forward, {lines[3].values[0], lines[3].values[1], lines[3].values[2]}, centre,
                                     size, where);
    return {std::move(camera), {std::move(invpol), false, -pol[0]}};
}

struct PyFile {
    Camera camera;
    OcamCalibInverse inverse;
};

PyFile parse_py(std::string_view text, const std::string& source, const std::optional<ImageSize>& size) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field top(root, "", source);
    const Field taylor = top.at({"taylor_coefficient"});
    const std::vector<double> forward = taylor.numbers(64);
    if (forward.empty()) taylor.fail("no coefficients");
    const Field centre_field = top.at({"distortion_center"});
    const std::vector<double> centre = centre_field.numbers(2);
    if (centre.size() != 2) centre_field.fail("expected (x, y), got " + centre_field.shown());
    const Field stretch = top.at({"stretch_matrix"});
    if (stretch.size() != 2) stretch.fail("expected [[c, d], [e, 1]], got " + stretch.shown());
    const std::vector<double> top_row = stretch.item(0).numbers(2), bottom_row = stretch.item(1).numbers(2);
    if (top_row.size() != 2 || bottom_row.size() != 2 || bottom_row[1] != 1.0) {
        stretch.fail("expected [[c, d], [e, 1]], got " + stretch.shown());
    }
    const Field inverse_field = top.at({"inverse_poly"});
    std::vector<double> inverse = inverse_field.numbers(1000);
    std::reverse(inverse.begin(), inverse.end());  // stored highest degree first
    if (!size) {
        top.fail("py-OCamCalib's JSON stores no image size: give it (--image-size WIDTHxHEIGHT)");
    }
    const double c = top_row[0], d = top_row[1], e = bottom_row[0];
    if (!(c > 0.0)) stretch.fail("c must be positive, got " + format_number(c));
    Camera camera = ocamcalib_camera_on_xy(forward, c, d, e, Vec2(centre[0], centre[1]), *size,
                                           source + ": \"taylor_coefficient\"");
    return {std::move(camera), {std::move(inverse), true, forward[0]}};
}

// The toolbox's findinvpoly: rho as a polynomial of theta = atan(z / rho) (its axes, z
// backwards), least squares over the image's radii, the degree raised until it misses by
// less than 0.01 px (or the best of degrees up to 24).
std::vector<double> fitted_inverse(const Camera& camera, double units_per_radius) {
    const auto& k = camera.lens.coefficients;
    const double inverse_determinant = 1.0 / (k[0] - k[1] * k[2]);
    double largest = 0.0;  // the largest sensor radius of the image's corners
    for (const double x : {-0.5, static_cast<double>(camera.size.width) - 0.5}) {
        for (const double y : {-0.5, static_cast<double>(camera.size.height) - 0.5}) {
            const double mx = (x - camera.intrinsics.cx) / camera.intrinsics.fx;
            const double my = (y - camera.intrinsics.cy) / camera.intrinsics.fy;
            largest = std::max(largest, std::hypot((k[0] * mx - k[2] * my) * inverse_determinant,
                                                   (my - k[1] * mx) * inverse_determinant));
        }
    }
    const double reach = std::min(largest, 0.999 * OcamCalibLens<double>::valid_radius(k));
    // Radii spaced evenly, and as many at angles spaced evenly (denser where the radius
    // grows fastest with the angle, towards the fold), each radius's exact angle.
    const std::span<const double> polynomial = std::span<const double>(k).subspan(3);
    const auto angle_at = [&](double r) {
        double slope = 0.0;
        return std::atan2(r, OcamCalibLens<double>::forward(polynomial, r, slope));
    };
    std::vector<double> at_angles = {1, 0, 0};
    at_angles.insert(at_angles.end(), polynomial.begin(), polynomial.end());
    const auto radial = OcamCalibLens<double>::parameters(at_angles);
    constexpr int kHalf = 300, kSamples = 2 * kHalf;
    Eigen::VectorXd theta(kSamples), rho(kSamples);
    for (int i = 0; i < kHalf; ++i) {
        const double even = reach * i / (kHalf - 1);
        Vec2 m = Vec2::Zero();
        const double angle = angle_at(reach) * i / (kHalf - 1);
        OcamCalibLens<double>::project(radial, Vec3(std::sin(angle), 0.0, std::cos(angle)), m);
        const double solved = std::min(std::abs(m.x()), reach);
        int j = 2 * i;
        for (const double r : {even, solved}) {
            theta(j) = angle_at(r) - std::numbers::pi / 2;  // the toolbox's atan(z / rho), z backwards
            rho(j++) = units_per_radius * r;
        }
    }
    std::vector<double> best;
    double best_miss = std::numeric_limits<double>::infinity();
    for (int degree = 1; degree <= 24 && best_miss >= 0.01; ++degree) {
        Eigen::MatrixXd powers(kSamples, degree + 1);
        for (int i = 0; i < kSamples; ++i) {
            double power = 1.0;
            for (int j = 0; j <= degree; ++j, power *= theta(i)) powers(i, j) = power;
        }
        const Eigen::VectorXd fit = powers.colPivHouseholderQr().solve(rho);
        const double miss = (powers * fit - rho).cwiseAbs().maxCoeff();
        if (miss < best_miss && fit.allFinite()) {
            best_miss = miss;
            best.assign(fit.data(), fit.data() + fit.size());
        }
    }
    return best;
}

std::string numbers_line(std::span<const double> values, bool counted_first) {
    std::string line = counted_first ? std::to_string(values.size()) : std::string();
    for (const double value : values) line += (line.empty() ? "" : " ") + format_number(value);
    return line + "\n";
}

}  // namespace

Camera ocamcalib_camera_on_xy(std::span<const double> forward, double c, double d, double e, Vec2 centre,
                              ImageSize size, const std::string& where) {
    if (!(c > 0.0)) throw FileError(where + ": the stretch's c must be positive, got " + format_number(c));
    // [[c, d], [e, 1]] on (x, y) is c [1, d / c; e / c, 1 / c]: the lens's affine, its scale c
    // taken into the sensor's units (fx = c P(0); the k_i = P_i P(0)^(i - 1) do not change).
    Camera camera = ocamcalib_camera(forward, {1.0 / c, e / c, d / c}, centre, size, where);
    camera.intrinsics.fx *= c;
    camera.intrinsics.fy *= c;
    return validated_camera(std::move(camera), where);
}

namespace {

// How many numbers a line holds, or -1 where a word is not a number.
int numbers_in(std::string_view line) {
    int count = 0;
    while (true) {
        const auto word = line.find_first_not_of(" \t\r");
        if (word == std::string_view::npos) return count;
        line.remove_prefix(word);
        const std::string_view token = line.substr(0, line.find_first_of(" \t\r"));
        double value = 0.0;
        const auto [stop, error] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (error != std::errc() || stop != token.data() + token.size()) return -1;
        ++count;
        line.remove_prefix(token.size());
    }
}

// Whether a "count c0 c1 ..." line's count is the number of the numbers after it.
bool counted_line(std::string_view line, int numbers) {
    int count = 0;
    const std::string_view first = line.substr(line.find_first_not_of(" \t\r"));
    const auto [stop, error] = std::from_chars(first.data(), first.data() + first.size(), count);
    return error == std::errc() && count >= 1 && count == numbers - 1;
}

}  // namespace

bool looks_like_ocamcalib(std::string_view text) {
    constexpr std::array<int, 5> kShape = {0, 0, 2, 3, 2};  // 0: a counted line
    std::size_t at = 0;
    std::size_t content = 0;
    bool shaped = true;
    while (at < text.size() && content <= kShape.size()) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::string_view line = text.substr(at, end - at);
        at = end + 1;
        const auto start = line.find_first_not_of(" \t\r");
        if (start == std::string_view::npos) continue;
        if (line[start] == '#') {
            const bool toolbox = line.find("DIRECT mapping function") != std::string_view::npos ||
                                 line.find("ocam_model") != std::string_view::npos;
            if (toolbox) return true;
            continue;
        }
        if (content < kShape.size()) {
            const int numbers = numbers_in(line);
            const bool fits = kShape[content] == 0 ? counted_line(line, numbers) : numbers == kShape[content];
            shaped = shaped && numbers > 0 && fits;
        }
        ++content;
    }
    return shaped && content == kShape.size();
}

std::vector<NamedCamera> read_ocamcalib(std::string_view text, const ReadContext& context) {
    ToolboxFile file = parse_toolbox(text, context.source);
    if (context.options.size && !(*context.options.size == file.camera.size)) {
        throw FileError(context.source + ": the file's image size is " + std::to_string(file.camera.size.width) + "x" +
                        std::to_string(file.camera.size.height) + ", the image size given is " +
                        std::to_string(context.options.size->width) + "x" + std::to_string(context.options.size->height));
    }
    return {{std::string(), {std::move(file.camera), std::nullopt}}};
}

std::string write_ocamcalib(const Camera& given, const WriteOptions& options) {
    given.validate();
    Camera camera = given;
    // A pinhole is OCAMCALIB with g(r) = 1 and the identity affine.
    if (camera.lens.type == LensType::Pinhole) camera.lens = {LensType::OcamCalib, {1, 0, 0, 0, 0, 0, 0, 0}};
    if (camera.lens.type != LensType::OcamCalib) {
        throw NotRepresentable("calib_results.txt holds OCamCalib's model (OCAMCALIB, or PINHOLE as one), not " +
                               std::string(lens_info(camera.lens.type).name));
    }
    if (camera.intrinsics.skew != 0.0) {
        throw NotRepresentable("calib_results.txt has no skew; this camera's is " + format_number(camera.intrinsics.skew));
    }
    if (!options.drop_pose && (camera.pose.R != Mat3::Identity() || camera.pose.t != Vec3::Zero())) {
        throw NotRepresentable("calib_results.txt holds no pose; this camera's is not the identity: write its "
                               "intrinsics alone with --no-pose");
    }
    const Intrinsics& K = camera.intrinsics;
    const auto& k = camera.lens.coefficients;
    // pixel - centre = fx [1, e; (fy / fx) d, (fy / fx) c] (fx n): the toolbox's sensor is
    // in pixels of fx, its affine takes fy / fx.
    const double aspect = K.fy / K.fx;
    std::vector<double> pol = {-K.fx};
    double power = 1.0;
    for (std::size_t i = 3; i < k.size(); ++i) {
        pol.push_back(-k[i] / power + 0.0);
        power *= K.fx;
    }
    // As many terms as the toolbox's default degree 4 writes, more only when used.
    while (pol.size() > 5 && pol.back() == 0.0) pol.pop_back();
    Camera scaled = camera;
    scaled.intrinsics.fy = K.fx;
    scaled.lens.coefficients[0] = k[0] * aspect;
    scaled.lens.coefficients[1] = k[1] * aspect;
    const std::vector<double> invpol = fitted_inverse(scaled, K.fx);
    return "#polynomial coefficients for the DIRECT mapping function (ocam_model.ss in MATLAB). These are used by "
           "cam2world\n\n" + numbers_line(pol, true) +
           "\n#polynomial coefficients for the inverse mapping function (ocam_model.invpol in MATLAB). These are used "
           "by world2cam\n\n" + numbers_line(invpol, true) +
           "\n#center: \"row\" and \"column\", starting from 0 (C convention)\n\n" +
           numbers_line(std::array{K.cy, K.cx}, false) + "\n#affine parameters \"c\", \"d\", \"e\"\n\n" +
           numbers_line(std::array{k[0] * aspect, k[1] * aspect, k[2]}, false) +
           "\n#image size: \"height\" and \"width\"\n\n" + std::to_string(camera.size.height) + " " +
           std::to_string(camera.size.width) + "\n\n";
}

bool claims_py_ocamcalib(const DocumentNode& root) {
    return root.find("taylor_coefficient") != nullptr && root.find("distortion_center") != nullptr;
}

std::vector<NamedCamera> read_py_ocamcalib(std::string_view text, const ReadContext& context) {
    const DocumentNode root = parse_json_tree(text, context.source);
    const DocumentNode* name = root.find("camera_name");
    PyFile file = parse_py(text, context.source, context.options.size);
    std::string camera_name;
    if (name != nullptr && name->kind == DocumentNode::Kind::Scalar) camera_name = name->text;
    return {{camera_name, {std::move(file.camera), std::nullopt}}};
}

std::optional<OcamCalibInverse> read_ocamcalib_inverse(const std::filesystem::path& path) {
    const detail::LocatedFile located = detail::locate_camera_file(path, std::nullopt);
    const std::string source = located.file.string();
    if (located.format == CameraFormat::OcamCalib) return parse_toolbox(located.text, source).inverse;
    if (located.format == CameraFormat::PyOcamCalib) return parse_py(located.text, source, ImageSize{1, 1}).inverse;
    return std::nullopt;
}

Vec2 ocamcalib_inverse_pixel(const Camera& camera, const OcamCalibInverse& inverse, const Vec3& point) {
    const double radius = std::hypot(point.x(), point.y());
    const double from_axis = std::atan2(radius, point.z());
    const double theta = inverse.of_angle_from_axis ? from_axis : from_axis - std::numbers::pi / 2;
    double rho = 0.0;
    for (auto c = inverse.coefficients.rbegin(); c != inverse.coefficients.rend(); ++c) rho = rho * theta + *c;
    const double scale = radius > 0.0 ? rho / (inverse.units_per_radius * radius) : 0.0;
    const Vec2 n(scale * point.x(), scale * point.y());
    const auto& k = camera.lens.coefficients;
    const Vec2 m(n.x() + k[2] * n.y(), k[1] * n.x() + k[0] * n.y());
    const Intrinsics& K = camera.intrinsics;
    return {K.fx * m.x() + K.skew * m.y() + K.cx, K.fy * m.y() + K.cy};
}

InverseMiss ocamcalib_inverse_miss(const Camera& camera, const OcamCalibInverse& inverse) {
    if (camera.lens.type != LensType::OcamCalib) {
        throw InvalidArgument("invpol: the camera's lens is " + std::string(lens_info(camera.lens.type).name) +
                              ", not OCAMCALIB");
    }
    Camera centred = camera;
    centred.pose = Pose{};
    const PreparedCamera prepared(centred);
    const double half_side = 0.5 * static_cast<double>(std::min(camera.size.width, camera.size.height));
    InverseMiss miss;
    std::vector<Vec2> row_pixels(static_cast<std::size_t>(camera.size.width));
    for (long y = 0; y < camera.size.height; ++y) {
        for (long x = 0; x < camera.size.width; ++x) row_pixels[static_cast<std::size_t>(x)] = Vec2(double(x), double(y));
        const std::vector<Unprojection> rays = prepared.unproject(row_pixels);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if (!rays[i].valid) continue;
            const Vec2& pixel = row_pixels[i];
            const double error = (ocamcalib_inverse_pixel(camera, inverse, rays[i].direction) - pixel).norm();
            if (error > miss.whole_image) {
                miss.whole_image = error;
                miss.worst_pixel = pixel;
            }
            const Vec2 offset(pixel.x() - camera.intrinsics.cx, pixel.y() - camera.intrinsics.cy);
            if (offset.norm() <= half_side) miss.within_half_side = std::max(miss.within_half_side, error);
        }
    }
    return miss;
}

}  // namespace libcam
