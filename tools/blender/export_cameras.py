"""Export a Blender scene's cameras as a file every libcam command reads.

Run inside Blender:

    blender -b scene.blend -P tools/blender/export_cameras.py -- cameras.json
    blender -b scene.blend -P tools/blender/export_cameras.py -- cameras.json --all

The first form writes the scene's active camera at the current frame. With --all, every
camera of the scene, by name; a camera whose pose or settings change over the scene's frame range
(an animation, a parent's, a constraint's) is written once per frame, named
"<camera>@<frame>", the others once.

The file holds Blender's own settings (bpy's names: lens and sensor in millimetres,
angles in radians, the camera object's world matrix), which libcam turns into K, the lens
and the pose:

    libcam info cameras.json
    libcam convert --from cameras.json --camera Camera@12 --to opencv-yaml
"""

import json
import sys

import bpy

FORMAT = "libcam Blender cameras"

PANORAMA_SETTINGS = {
    "FISHEYE_EQUIDISTANT": ("fisheye_fov",),
    "FISHEYE_EQUISOLID": ("fisheye_fov", "fisheye_lens"),
    "FISHEYE_LENS_POLYNOMIAL": ("fisheye_fov", "fisheye_polynomial_k0", "fisheye_polynomial_k1",
                                "fisheye_polynomial_k2", "fisheye_polynomial_k3", "fisheye_polynomial_k4"),
    "EQUIRECTANGULAR": ("latitude_min", "latitude_max", "longitude_min", "longitude_max"),
}


def camera_settings(scene, camera):
    """The settings of one camera object at the scene's current frame."""
    render = scene.render
    data = camera.data
    settings = {
        "name": camera.name,
        "resolution_x": render.resolution_x,
        "resolution_y": render.resolution_y,
        "resolution_percentage": render.resolution_percentage,
        "pixel_aspect_x": render.pixel_aspect_x,
        "pixel_aspect_y": render.pixel_aspect_y,
        "type": data.type,
        "lens": data.lens,
        "sensor_width": data.sensor_width,
        "sensor_height": data.sensor_height,
        "sensor_fit": data.sensor_fit,
        "shift_x": data.shift_x,
        "shift_y": data.shift_y,
        "clip_start": data.clip_start,
        "clip_end": data.clip_end,
    }
    if data.type == "PANO":
        # Blender 3.x keeps the panorama settings on data.cycles, later versions on data.
        panorama = data if hasattr(data, "panorama_type") else data.cycles
        settings["panorama_type"] = panorama.panorama_type
        for key in PANORAMA_SETTINGS.get(panorama.panorama_type, ()):
            settings[key] = getattr(panorama, key)
    settings["matrix_world"] = [list(row) for row in camera.matrix_world]
    return settings


def animated_settings(scene, camera):
    """The camera's settings at every frame of the scene's range, or once if they never change."""
    frames = range(scene.frame_start, scene.frame_end + 1, max(scene.frame_step, 1))
    current = scene.frame_current
    per_frame = []
    for frame in frames:
        scene.frame_set(frame)
        per_frame.append((frame, camera_settings(scene, camera)))
    scene.frame_set(current)
    if all(settings == per_frame[0][1] for _, settings in per_frame):
        return [camera_settings(scene, camera)]
    return [dict(settings, frame=frame) for frame, settings in per_frame]


def main(arguments):
    if not arguments or arguments[0].startswith("-") or any(a not in ("--all",) for a in arguments[1:]):
        raise SystemExit("usage: blender -b scene.blend -P export_cameras.py -- OUTPUT.json [--all]")
    output = arguments[0]
    scene = bpy.context.scene
    if "--all" in arguments[1:]:
        cameras = sorted((obj for obj in scene.objects if obj.type == "CAMERA"), key=lambda obj: obj.name)
        if not cameras:
            raise SystemExit("export_cameras: the scene has no camera")
        entries = [entry for camera in cameras for entry in animated_settings(scene, camera)]
    else:
        if scene.camera is None:
            raise SystemExit("export_cameras: the scene has no active camera (give --all for every camera)")
        entries = [camera_settings(scene, scene.camera)]
    with open(output, "w", encoding="utf-8") as file:
        json.dump({"format": FORMAT, "cameras": entries}, file, indent=2)
        file.write("\n")
    print(f"export_cameras: {len(entries)} camera(s) written to {output}")


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
