// RealityCapture's XMP sidecars: small files laid out as RealityCapture writes them (its
// attributes on rdf:Description, Rotation, Position and DistortionCoeficients as
// elements), whose cameras are worked out by hand from the conventions the format's
// header names (RealityCapture's "XMP Camera Math" article; camorph's, EasyVolcap's and
// pyalicevision's converters): fx = FocalLength35mm S / 36 with S the longer side, the
// principal point U S, V S from the image's centre, t1 t2 swapped against OpenCV's p1 p2,
// Rotation world to camera, Position the centre.

#include <catch2/catch.hpp>
#include <algorithm>
#include <string>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "error_message.hpp"

using namespace libcam;
using libcam::test::file_error_of;

namespace {

std::string xmp(const std::string& attributes, const std::string& elements) {
    return R"(<x:xmpmeta xmlns:x="adobe:ns:meta/">
  <rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#">
    <rdf:Description xmlns:xcr="http://www.capturingreality.com/ns/xcr/1.1#" xcr:Version="3"
       xcr:PosePrior="initial" xcr:Coordinates="absolute" )" +
           attributes + R"(>
      )" + elements + R"(
    </rdf:Description>
  </rdf:RDF>
</x:xmpmeta>
)";
}

const std::string kBrown3t2 = xmp(
    R"(xcr:DistortionModel="brown3t2" xcr:FocalLength35mm="24" xcr:Skew="0" xcr:AspectRatio="1.001"
       xcr:PrincipalPointU="0.01" xcr:PrincipalPointV="-0.005")",
    R"(<xcr:Rotation>0 1 0 -1 0 0 0 0 1</xcr:Rotation>
      <xcr:Position>10 20 30</xcr:Position>
      <xcr:DistortionCoeficients>-0.1 0.02 -0.003 0 0.0004 -0.0005</xcr:DistortionCoeficients>)");

ReadOptions sized(long width, long height) {
    ReadOptions options;
    options.size = ImageSize{width, height};
    return options;
}

Camera read(const std::string& text, ReadOptions options, const std::string& name = "IMG_0001.xmp") {
    return parse_camera(text, CameraFormat::RealityCapture, name, options).camera;
}

// RealityCapture's pixel of a camera-frame point by its "XMP Camera Math" (as the format's
// header gives it), term by term: Brown's four radial terms and t1 t2 on (X/Z, Y/Z), then
// image coordinates in units of the longer side S from the image's centre, pixel (0, 0) the
// top-left pixel's corner (so its centre is 0.5 off libcam's).
struct RcTerms {
    double width, height, focal_35mm, aspect, u, v, k1, k2, k3, k4, t1, t2;
};

Vec2 realitycapture_pixel(const RcTerms& c, const Vec3& point) {
    const double x = point.x() / point.z(), y = point.y() / point.z();
    const double r2 = x * x + y * y;
    const double radial = 1 + c.k1 * r2 + c.k2 * r2 * r2 + c.k3 * r2 * r2 * r2 + c.k4 * r2 * r2 * r2 * r2;
    const double xd = x * radial + c.t1 * (r2 + 2 * x * x) + 2 * c.t2 * x * y;
    const double yd = y * radial + c.t2 * (r2 + 2 * y * y) + 2 * c.t1 * x * y;
    const double side = std::max(c.width, c.height), f = c.focal_35mm / 36.0;
    return {c.width / 2 + side * (f * xd + c.u) - 0.5, c.height / 2 + side * (c.aspect * f * yd + c.v) - 0.5};
}

}  // namespace

TEST_CASE("realitycapture: brown3t2 is OPENCV5 with t1 t2 swapped, the focal length on the longer side") {
    const Camera camera = read(kBrown3t2, sized(6000, 4000));
    CHECK(camera.size == ImageSize{6000, 4000});
    // fx = 24 * 6000 / 36 = 4000; fy = 1.001 * 4000 = 4004; cx = 6000 / 2 - 0.5 + 0.01 * 6000
    // = 3059.5; cy = 4000 / 2 - 0.5 - 0.005 * 6000 = 1969.5.
    CHECK(camera.intrinsics.fx == Approx(4000.0).epsilon(1e-15));
    CHECK(camera.intrinsics.fy == Approx(4004.0).epsilon(1e-15));
    CHECK(camera.intrinsics.cx == Approx(3059.5).epsilon(1e-15));
    CHECK(camera.intrinsics.cy == Approx(1969.5).epsilon(1e-15));
    CHECK(camera.intrinsics.skew == 0.0);
    // k1 k2 k3 k4 t1 t2 = -0.1 0.02 -0.003 0 0.0004 -0.0005: OpenCV's p1 = t2, p2 = t1.
    CHECK(camera.lens == Lens{LensType::OpenCv5, {-0.1, 0.02, -0.0005, 0.0004, -0.003}});
    // Rotation is world to camera; t = -R C = -(20, -10, 30).
    CHECK(camera.pose.R == (Mat3() << 0, 1, 0, -1, 0, 0, 0, 0, 1).finished());
    CHECK(camera.pose.t == Vec3(-20, 10, -30));
}

TEST_CASE("realitycapture: brown4 and brown4t2 with k4 (r^8) are BROWN_K4 and project as RealityCapture's formula") {
    const RcTerms terms{6000, 4000, 24, 1.001, 0.01, -0.005, -0.1, 0.02, -0.003, 0.0015, 0.0004, -0.0005};
    const Camera camera = read(xmp(R"(xcr:DistortionModel="brown4t2" xcr:FocalLength35mm="24" xcr:AspectRatio="1.001"
       xcr:PrincipalPointU="0.01" xcr:PrincipalPointV="-0.005")",
                                   "<xcr:DistortionCoeficients>-0.1 0.02 -0.003 0.0015 0.0004 -0.0005"
                                   "</xcr:DistortionCoeficients>"),
                               sized(6000, 4000));
    CHECK(camera.lens == Lens{LensType::BrownK4, {-0.1, 0.02, -0.0005, 0.0004, -0.003, 0.0015}});
    const PreparedCamera prepared(camera);
    for (const Vec3& point : {Vec3(0, 0, 1), Vec3(0.3, -0.2, 1), Vec3(-0.45, 0.3, 1.2), Vec3(0.5, 0.33, 1)}) {
        const Projection got = prepared.project(point);
        REQUIRE(got.valid);
        CHECK((got.pixel - realitycapture_pixel(terms, point)).norm() < 1e-9);
    }
    const Camera brown4 = read(xmp(R"(xcr:DistortionModel="brown4" xcr:FocalLength35mm="30")",
                                   "<xcr:DistortionCoeficients>-0.1 0 0 0.001 0 0</xcr:DistortionCoeficients>"),
                               sized(640, 480));
    CHECK(brown4.lens == Lens{LensType::BrownK4, {-0.1, 0, 0, 0, 0, 0.001}});
}

TEST_CASE("realitycapture: a portrait image measures the focal length and principal point on its height") {
    const Camera camera = read(kBrown3t2, sized(4000, 6000));
    // S = 6000 still: fx = 4000, cx = 2000 - 0.5 + 60 = 2059.5, cy = 3000 - 0.5 - 30 = 2969.5.
    CHECK(camera.intrinsics.fx == Approx(4000.0).epsilon(1e-15));
    CHECK(camera.intrinsics.cx == Approx(2059.5).epsilon(1e-15));
    CHECK(camera.intrinsics.cy == Approx(2969.5).epsilon(1e-15));
}

TEST_CASE("realitycapture: brown3, perspective and values as elements") {
    const Camera brown3 = read(xmp(R"(xcr:DistortionModel="brown3" xcr:FocalLength35mm="36")",
                                   "<xcr:DistortionCoeficients>-0.2 0.05 0 0 0 0</xcr:DistortionCoeficients>"),
                               sized(1000, 800));
    CHECK(brown3.lens == Lens{LensType::OpenCv4, {-0.2, 0.05, 0.0, 0.0}});
    CHECK(brown3.intrinsics.fx == 1000.0);  // 36 mm on a 36 mm side: the longer side in pixels
    CHECK(brown3.intrinsics.cx == 499.5);
    CHECK(brown3.intrinsics.cy == 399.5);
    CHECK(brown3.pose.R == Mat3::Identity());  // no Rotation nor Position: no pose
    const Camera elements = read(xmp("", R"(<xcr:DistortionModel>perspective</xcr:DistortionModel>
      <xcr:FocalLength35mm>18</xcr:FocalLength35mm>)"),
                                 sized(2000, 1000));
    CHECK(elements.lens.type == LensType::Pinhole);
    CHECK(elements.intrinsics.fx == 1000.0);
    // A prefix other than "xcr", bound to the same namespace.
    const Camera prefixed = read(R"(<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#">
  <rdf:Description xmlns:rc="http://www.capturingreality.com/ns/xcr/1.1#" rc:FocalLength35mm="72"/></rdf:RDF>)",
                                 sized(100, 50));
    CHECK(prefixed.intrinsics.fx == 200.0);
}

TEST_CASE("realitycapture: the file from its name, with the image size given") {
    const CameraSet set = parse_camera_set(kBrown3t2, CameraFormat::RealityCapture, "a.xmp", sized(6000, 4000));
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.format == CameraFormat::RealityCapture);
}

TEST_CASE("realitycapture: what libcam cannot hold, and malformed files, are refused in one line") {
    CHECK(file_error_of([&] { (void)read(kBrown3t2, {}); }) ==
          "IMG_0001.xmp: RealityCapture's XMP does not hold the image size, which its focal length and principal point "
          "are relative to: give it (--image-size WxH)");
    const auto refusal = [](const std::string& text) {
        try {
            (void)read(text, sized(640, 480));
        } catch (const NotRepresentable& error) {
            return std::string(error.what());
        }
        return std::string("not refused");
    };
    CHECK(refusal(xmp(R"(xcr:DistortionModel="division" xcr:FocalLength35mm="30")",
                      "<xcr:DistortionCoeficients>-0.1 0 0 0 0 0</xcr:DistortionCoeficients>")) ==
          "IMG_0001.xmp: xcr:DistortionCoeficients: division with k1 = -0.1: the unit of RealityCapture's division "
          "coefficient is not documented, so it is not read as libcam's DIVISION");
    CHECK(refusal(xmp(R"(xcr:FocalLength35mm="30" xcr:Skew="0.1")", "")) ==
          "IMG_0001.xmp: xcr:Skew: a skew of 0.1 is not read (its unit is not documented)");
    const auto error_of = [](const std::string& text) { return file_error_of([&] { (void)read(text, sized(640, 480)); }); };
    CHECK(error_of(xmp(R"(xcr:DistortionModel="fisheye" xcr:FocalLength35mm="30")", "")) ==
          "IMG_0001.xmp: xcr:DistortionModel: must be perspective, brown3, brown4, brown3t2, brown4t2 or division, got "
          "'fisheye'");
    CHECK(error_of(xmp(R"(xcr:DistortionModel="brown3" xcr:FocalLength35mm="30")",
                       "<xcr:DistortionCoeficients>-0.1 0 0 0 0.001 0</xcr:DistortionCoeficients>")) ==
          "IMG_0001.xmp: xcr:DistortionCoeficients: t1 = 0.001 is not a term of brown3");
    CHECK(error_of(xmp(R"(xcr:FocalLength35mm="30")", "<xcr:Rotation>1 0 0 0 1 0 0 0</xcr:Rotation>"
                                                      "<xcr:Position>0 0 0</xcr:Position>")) ==
          "IMG_0001.xmp: xcr:Rotation: expected 9 numbers, got 8");
    CHECK(error_of(xmp(R"(xcr:FocalLength35mm="30")", "<xcr:Rotation>1 0 0 0 1 0 0 0 1</xcr:Rotation>")) ==
          "IMG_0001.xmp: xcr:Position: missing");
    CHECK(error_of(xmp(R"(xcr:FocalLength35mm="nan")", "")) ==
          "IMG_0001.xmp: xcr:FocalLength35mm: must be finite numbers, got 'nan'");
    CHECK(error_of(xmp("", "")) == "IMG_0001.xmp: xcr:FocalLength35mm: missing");
    CHECK(error_of(R"(<x:xmpmeta xmlns:x="adobe:ns:meta/"><rdf:RDF/></x:xmpmeta>)") ==
          "IMG_0001.xmp: no rdf:Description in RealityCapture's namespace "
          "(http://www.capturingreality.com/ns/xcr/1.1#)");
    CHECK_THAT(error_of("<x:xmpmeta"), Catch::StartsWith("IMG_0001.xmp: line 1: not valid XML: "));
    // A rotation that is not one: the camera's own check, naming the file.
    CHECK_THAT(error_of(xmp(R"(xcr:FocalLength35mm="30")", "<xcr:Rotation>2 0 0 0 1 0 0 0 1</xcr:Rotation>"
                                                           "<xcr:Position>0 0 0</xcr:Position>")),
               Catch::StartsWith("IMG_0001.xmp: "));
}
