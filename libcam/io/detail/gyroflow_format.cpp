#include "libcam/io/detail/gyroflow_format.hpp"

#include <optional>
#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/image_size.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// The lens of Gyroflow's model `name` with its coefficients (the header's table).
Lens gyroflow_lens(const std::string& name, const Field& coefficients) {
    const std::vector<double> k = coefficients.numbers(12);
    const auto need = [&](std::size_t count) {
        if (k.size() < count) {
            coefficients.fail("the " + name + " model needs " + std::to_string(count) + " coefficients, got " +
                              std::to_string(k.size()));
        }
        for (std::size_t i = count; i < k.size(); ++i) {
            if (k[i] != 0.0) {
                coefficients.fail("the " + name + " model uses " + std::to_string(count) + " coefficients; coefficient " +
                                  std::to_string(i) + " is " + format_number(k[i]));
            }
        }
    };
    if (name == "opencv_fisheye") {
        need(4);
        return {LensType::Fisheye, {k[0], k[1], k[2], k[3]}};
    }
    if (name == "opencv_standard") {
        std::vector<double> all = k;
        all.resize(12, 0.0);
        return simplest_equal_lens({LensType::OpenCv12, all});
    }
    if (name == "poly3") {
        need(1);
        return simplest_equal_lens({LensType::OpenCv4, {k[0], 0.0, 0.0, 0.0}});
    }
    if (name == "poly5") {
        need(2);
        return simplest_equal_lens({LensType::OpenCv4, {k[0], k[1], 0.0, 0.0}});
    }
    if (name == "ptlens") {
        need(3);
        if (k[0] == 0.0 && k[2] == 0.0) return simplest_equal_lens({LensType::OpenCv4, {k[1], 0.0, 0.0, 0.0}});
        return {LensType::Ptlens, {k[0], k[1], k[2]}};
    }
    throw NotRepresentable(coefficients.source() + ": distortion_model " + shown_value(name) +
                           " has no libcam model (libcam reads opencv_fisheye, opencv_standard, poly3, poly5 and "
                           "ptlens)");
}

}  // namespace

bool claims_gyroflow(const DocumentNode& root) {
    return root.find("calib_dimension") != nullptr && root.find("fisheye_params") != nullptr;
}

std::vector<NamedCamera> read_gyroflow(std::string_view text, const ReadContext& context) {
    const DocumentNode root = parse_json_tree(text, context.source);
    const Field top(root, "", context.source);
    const Field dimension = top.at({"calib_dimension"});
    Camera camera;
    camera.size = {static_cast<long>(dimension.at({"w"}).whole_number(1, kMaxImageSide)),
                   static_cast<long>(dimension.at({"h"}).whole_number(1, kMaxImageSide))};
    for (const char* stretch : {"input_horizontal_stretch", "input_vertical_stretch"}) {
        if (const std::optional<Field> field = top.find({stretch})) {
            const double value = field->number();
            // Gyroflow reads 0 (and anything up to 0.01) as 1.
            if (value > 0.01 && value != 1.0) {
                throw NotRepresentable(context.source + ": \"" + stretch + "\": an anamorphic stretch (" +
                                       format_number(value) + ") is not read");
            }
        }
    }
    const Field params = top.at({"fisheye_params"});
    const Field matrix = params.at({"camera_matrix"});
    if (matrix.size() != 3) matrix.fail("expected 3 rows, got " + std::to_string(matrix.size()));
    double k[3][3];
    for (std::size_t r = 0; r < 3; ++r) {
        const Field row = matrix.item(r);
        if (row.size() != 3) row.fail("expected 3 numbers, got " + std::to_string(row.size()));
        for (std::size_t c = 0; c < 3; ++c) k[r][c] = row.item(c).number();
    }
    if (k[1][0] != 0.0 || k[2][0] != 0.0 || k[2][1] != 0.0 || k[2][2] != 1.0) {
        matrix.fail("expected [[fx, s, cx], [0, fy, cy], [0, 0, 1]]");
    }
    const std::optional<Field> asymmetrical = top.find({"asymmetrical"});
    const bool own_centre = asymmetrical && asymmetrical->boolean().value_or(false);
    camera.intrinsics = {k[0][0], k[1][1], own_centre ? k[0][2] : camera.size.width / 2.0,
                         own_centre ? k[1][2] : camera.size.height / 2.0, k[0][1]};
    const std::optional<Field> model = top.find({"distortion_model"});
    const std::string model_name = model ? model->text() : std::string("opencv_fisheye");
    camera.lens = gyroflow_lens(model_name, params.at({"distortion_coeffs"}));
    std::string name;
    for (const char* key : {"camera_brand", "camera_model", "lens_model", "camera_setting"}) {
        if (const std::optional<Field> field = top.find({key}); field && field->node().kind == DocumentNode::Kind::Scalar) {
            const std::string part = field->text();
            if (!part.empty()) name += (name.empty() ? "" : " ") + part;
        }
    }
    return {{name, {validated_camera(camera, context.source), std::nullopt}}};
}

}  // namespace libcam
