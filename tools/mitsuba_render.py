#!/usr/bin/env python3
"""Render a glTF 2.0 scene with Mitsuba 3 as an independent reference for Bounce Lab.

This is a validation tool only (not part of the product or CI): it re-implements the
subset of glTF that Bounce Lab uses with a self-written loader (no third-party glTF
library) and renders it with Mitsuba's `path` integrator, so Bounce Lab's units and
conventions can be compared against an unrelated path tracer.

Usage:
    python3 tools/mitsuba_render.py SCENE.gltf --out OUT.exr --width W --height H \
        --spp N --max-bounces K [--seed S] [--sky R,G,B | --sky FILE.exr]
        [--sky-intensity X] [--sky-rotation DEG]
        [--variant llvm_ad_rgb] [--rr-depth D] [--sampler independent|stratified|multijitter|sobol]

Conventions used:
  * Every triangle primitive -> one-sided Mitsuba `diffuse` BSDF with reflectance =
    baseColorFactor.rgb (textures, metallic, roughness ignored). Back faces are black
    but still occlude. Positions/normals are baked to world space.
  * KHR_lights_punctual: point `color*intensity` = radiant intensity [W/sr];
    directional `color*intensity` = irradiance [W/m^2] along the node's -Z. Intensities
    are candela and lux (divided by 683 lm/W), as the glTF specification and Bounce Lab's
    import read them, unless the root `extras.bouncelab.light_units` says "radiometric";
    spot = Mitsuba `spot` whose angular profile is replaced by a projected bitmap of
    the KHR falloff saturate(cos*scale+offset)^2 (bilinear, 512^2). `range` ignored.
  * Emission: emissiveFactor x KHR_materials_emissive_strength (x 1/683 when photometric)
    -> a Mitsuba `area` emitter on the mesh (one-sided, front face; emissive textures ignored).
  * Sky (--sky, as Bounce Lab's flag): R,G,B -> `constant` emitter of that radiance (x 1/683
    when photometric); FILE.exr -> `envmap` turned so that Bounce Lab's equirectangular
    mapping (u = atan2(z, x) / 2pi, v = acos(y) / pi; Mitsuba's is u = atan2(x, -z) / 2pi)
    and --sky-rotation (degrees about +Y) agree; Mitsuba filters the image bilinearly where
    Bounce Lab takes the nearest texel, so compare with smooth skies.
  * First camera in depth-first node order; yfov = vertical FOV; aspect = W/H.
  * Film: hdrfilm with a box filter (each sample lands only in its own pixel, i.e. a
    pixel is the average over its area), the independent sampler unless --sampler says otherwise.
  * Integrator: path, max_depth = K+1 (K=1: direct light only), rr_depth = 1000 unless
    --rr-depth says otherwise, i.e. Russian roulette is effectively disabled (unbiased either
    way, just less noise); Mitsuba's own default is 5.
  * Variant: scalar_rgb unless --variant says otherwise. The llvm_* variants (vectorised, the
    fast ones) need LLVM >= 16: Debian 12's LLVM 15 crashes, its libllvm19 package works; the
    library is found at /usr/lib/x86_64-linux-gnu/libLLVM-19.so (or set DRJIT_LIBLLVM_PATH).
Output is linear radiance, float32 RGB EXR, row 0 = top of the image.
"""
import argparse, base64, json, math, os, sys, time
import numpy as np

LLVM_CANDIDATES = ["/usr/lib/x86_64-linux-gnu/libLLVM-19.so", "/usr/lib/x86_64-linux-gnu/libLLVM-18.so",
                   "/usr/lib/x86_64-linux-gnu/libLLVM-17.so", "/usr/lib/x86_64-linux-gnu/libLLVM-16.so"]


def select_variant(variant):
    """Imports Mitsuba with `variant`; for llvm_* points Dr.Jit at an LLVM >= 16 first."""
    if variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in os.environ:
        found = next((c for c in LLVM_CANDIDATES if os.path.exists(c)), None)
        if found is None:
            sys.exit(f"{variant} needs LLVM >= 16 (Debian 12: apt-get install libllvm19) or DRJIT_LIBLLVM_PATH")
        os.environ["DRJIT_LIBLLVM_PATH"] = found
    global mi
    import mitsuba
    mi = mitsuba
    mi.set_variant(variant)


mi = None

COMP = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def warn(msg):
    print("warning:", msg, file=sys.stderr)


def load_buffers(gltf, base_dir):
    out = []
    for b in gltf.get("buffers", []):
        uri = b["uri"]
        if uri.startswith("data:"):
            data = base64.b64decode(uri.split(",", 1)[1])
        else:
            from urllib.parse import unquote
            with open(os.path.join(base_dir, unquote(uri)), "rb") as f:
                data = f.read()
        out.append(data)
    return out


def read_accessor(gltf, buffers, idx):
    acc = gltf["accessors"][idx]
    dt, n, count = np.dtype(COMP[acc["componentType"]]), NCOMP[acc["type"]], acc["count"]
    if "bufferView" not in acc:
        return np.zeros((count, n), dt)
    bv = gltf["bufferViews"][acc["bufferView"]]
    start = bv.get("byteOffset", 0) + acc.get("byteOffset", 0)
    elem = dt.itemsize * n
    stride = bv.get("byteStride") or elem
    raw = np.frombuffer(buffers[bv["buffer"]], np.uint8)
    rows = raw[start:start + stride * (count - 1) + elem]
    rows = np.lib.stride_tricks.as_strided(rows, (count, elem), (stride, 1))
    return np.ascontiguousarray(rows).view(dt).reshape(count, n)


def local_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], np.float64).reshape(4, 4).T  # column-major
    t = node.get("translation", [0, 0, 0])
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    s = node.get("scale", [1, 1, 1])
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    M = np.eye(4)
    M[:3, :3] = R @ np.diag(s)
    M[:3, 3] = t
    return M


def walk(gltf):
    """Yield (node, world_matrix) depth-first over the default scene."""
    nodes = gltf.get("nodes", [])
    if gltf.get("scenes"):
        roots = gltf["scenes"][gltf.get("scene", 0)]["nodes"]
    else:
        kids = {c for n in nodes for c in n.get("children", [])}
        roots = [i for i in range(len(nodes)) if i not in kids]
    stack = [(i, np.eye(4)) for i in reversed(roots)]
    while stack:
        i, parent = stack.pop()
        W = parent @ local_matrix(nodes[i])
        yield nodes[i], W
        stack.extend((c, W) for c in reversed(nodes[i].get("children", [])))


def xf_point(M, p):
    return (M @ np.append(p, 1.0))[:3]


def xf_dir(M, d):
    v = M[:3, :3] @ np.asarray(d, float)
    return v / np.linalg.norm(v)


def lookat(origin, direction, M):
    up = xf_dir(M, [0, 1, 0])
    if abs(np.dot(up, direction)) > 0.999:
        up = xf_dir(M, [1, 0, 0])
    return mi.ScalarTransform4f().look_at(origin=origin.tolist(), target=(origin + direction).tolist(), up=up.tolist())


def make_mesh(name, gltf, buffers, prim, W, per_unit=1.0):
    if prim.get("mode", 4) != 4:
        warn(f"{name}: primitive mode {prim.get('mode')} is not triangles; skipped")
        return None
    attrs = prim["attributes"]
    P = read_accessor(gltf, buffers, attrs["POSITION"]).astype(np.float64)
    P = (P @ W[:3, :3].T + W[:3, 3]).astype(np.float32)
    N = None
    if "NORMAL" in attrs:
        N = read_accessor(gltf, buffers, attrs["NORMAL"]).astype(np.float64) @ np.linalg.inv(W[:3, :3])
        N = (N / np.maximum(np.linalg.norm(N, axis=1, keepdims=True), 1e-30)).astype(np.float32)
    if "indices" in prim:
        F = read_accessor(gltf, buffers, prim["indices"]).astype(np.uint32).reshape(-1, 3)
    else:
        F = np.arange(len(P), dtype=np.uint32).reshape(-1, 3)
    if np.linalg.det(W[:3, :3]) < 0:
        F = F[:, [0, 2, 1]]
    rgb = [1.0, 1.0, 1.0]
    emission = None
    if "material" in prim:
        mat = gltf["materials"][prim["material"]]
        rgb = mat.get("pbrMetallicRoughness", {}).get("baseColorFactor", [1, 1, 1, 1])[:3]
        strength = mat.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        e = [float(c) * strength * per_unit for c in mat.get("emissiveFactor", [0, 0, 0])]
        if max(e) > 0:
            emission = e
    props = mi.Properties()
    props["bsdf"] = mi.load_dict({"type": "diffuse", "reflectance": {"type": "rgb", "value": [float(c) for c in rgb]}})
    if emission is not None:
        props["emitter"] = mi.load_dict({"type": "area", "radiance": {"type": "rgb", "value": emission}})
    mesh = mi.Mesh(name, len(P), len(F), props=props, has_vertex_normals=N is not None)
    params = mi.traverse(mesh)
    params["vertex_positions"] = P.ravel()
    params["faces"] = np.ascontiguousarray(F).ravel()
    if N is not None:
        params["vertex_normals"] = N.ravel()
    params.update()
    return mesh


def spot_falloff_texture(inner, outer, cutoff, res=512):
    """Bitmap over Mitsuba's spot uv (u-0.5)*2*tan(cutoff) = x/z holding the KHR falloff."""
    t = (np.arange(res) + 0.5) / res * 2 - 1
    X, Y = np.meshgrid(t * math.tan(cutoff), t * math.tan(cutoff))
    cos = 1 / np.sqrt(1 + X * X + Y * Y)
    scale = 1 / max(1e-3, math.cos(inner) - math.cos(outer))
    f = np.clip(cos * scale - math.cos(outer) * scale, 0, 1) ** 2
    img = np.repeat(f[:, :, None], 3, axis=2).astype(np.float32)
    return {"type": "bitmap", "bitmap": mi.Bitmap(img), "raw": True,
            "filter_type": "bilinear", "wrap_mode": "clamp"}


def make_light(L, W, i, per_unit):
    rgb = (np.array(L.get("color", [1, 1, 1]), float) * L.get("intensity", 1.0) * per_unit).tolist()
    pos = xf_point(W, [0, 0, 0])
    fwd = xf_dir(W, [0, 0, -1])
    if "range" in L:
        warn(f"light {i}: 'range' ignored (Mitsuba lights have no range cut-off)")
    kind = L["type"]
    if kind == "point":
        return {"type": "point", "position": pos.tolist(), "intensity": {"type": "rgb", "value": rgb}}
    if kind == "directional":
        return {"type": "directional", "direction": fwd.tolist(), "irradiance": {"type": "rgb", "value": rgb}}
    if kind == "spot":
        sp = L.get("spot", {})
        inner, outer = sp.get("innerConeAngle", 0.0), sp.get("outerConeAngle", math.pi / 4)
        # Mitsuba's own linear-in-angle ramp is pushed just outside the outer cone (where the
        # KHR falloff is already 0); the KHR profile itself comes from the projected texture.
        cutoff = min(outer + 1e-3, math.radians(89.0))
        return {"type": "spot", "to_world": lookat(pos, fwd, W), "intensity": {"type": "rgb", "value": rgb},
                "cutoff_angle": math.degrees(cutoff), "beam_width": math.degrees(outer),
                "texture": spot_falloff_texture(inner, outer, cutoff)}
    warn(f"light {i}: unknown type {kind}; skipped")
    return None


def make_sky(sky, intensity, rotation, per_unit):
    """The Mitsuba emitter of Bounce Lab's --sky (see the module docs), or None."""
    if sky is None or sky == "none":
        return None
    parts = sky.split(",")
    if len(parts) == 3:
        rgb = [float(p) * per_unit * intensity for p in parts]
        return {"type": "constant", "radiance": {"type": "rgb", "value": rgb}}
    # Bounce Lab's sky frame -> Mitsuba's local frame: local = (z, y, -x) of the sky frame;
    # the sky frame is the world turned by -rotation about +Y.
    to_local = mi.ScalarTransform4f([[0, 0, 1, 0], [0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 0, 1]])
    to_world = mi.ScalarTransform4f().rotate([0, 1, 0], rotation) @ to_local.inverse()
    return {"type": "envmap", "filename": sky, "scale": intensity * per_unit, "to_world": to_world}


def build_scene(path, width, height, spp, max_bounces, sky=None, sky_intensity=1.0, sky_rotation=0.0,
                rr_depth=1000, sampler="independent"):
    with open(path) as f:
        gltf = json.load(f)
    buffers = load_buffers(gltf, os.path.dirname(os.path.abspath(path)))
    scene = {"type": "scene",
             "integrator": {"type": "path", "max_depth": max_bounces + 1, "rr_depth": rr_depth}}
    lights = gltf.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    units = gltf.get("extras", {}).get("bouncelab", {}).get("light_units", "photometric")
    per_unit = 1.0 if units == "radiometric" else 1.0 / 683.0
    sensor = None
    for k, (node, W) in enumerate(walk(gltf)):
        if "mesh" in node:
            for j, prim in enumerate(gltf["meshes"][node["mesh"]]["primitives"]):
                m = make_mesh(f"n{k}_p{j}", gltf, buffers, prim, W, per_unit)
                if m is not None:
                    scene[f"mesh_{k}_{j}"] = m
        li = node.get("extensions", {}).get("KHR_lights_punctual", {}).get("light")
        if li is not None:
            d = make_light(lights[li], W, li, per_unit)
            if d is not None:
                scene[f"light_{k}"] = d
        if "camera" in node and sensor is None:
            cam = gltf["cameras"][node["camera"]]
            if cam["type"] != "perspective":
                sys.exit("only perspective cameras are supported")
            p = cam["perspective"]
            sensor = {"type": "perspective", "fov_axis": "y", "fov": math.degrees(p["yfov"]),
                      "near_clip": p.get("znear", 0.01), "far_clip": p.get("zfar", 1e4),
                      # Mitsuba cameras look down local +Z; glTF cameras down local -Z.
                      "to_world": lookat(xf_point(W, [0, 0, 0]), xf_dir(W, [0, 0, -1]), W),
                      "film": {"type": "hdrfilm", "width": width, "height": height,
                               "pixel_format": "rgb", "component_format": "float32",
                               "rfilter": {"type": "box"}},
                      "sampler": {"type": sampler, "sample_count": spp}}
    if sensor is None:
        sys.exit("scene has no camera")
    scene["sensor"] = sensor
    sky_emitter = make_sky(sky, sky_intensity, sky_rotation, per_unit)
    if sky_emitter is not None:
        scene["sky"] = sky_emitter
    return mi.load_dict(scene)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--out", required=True)
    ap.add_argument("--width", type=int, required=True)
    ap.add_argument("--height", type=int, required=True)
    ap.add_argument("--spp", type=int, required=True)
    ap.add_argument("--max-bounces", type=int, required=True, help="1 = direct light only")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--sky", help="R,G,B (a constant sky in the scene's light units) or an equirectangular .exr")
    ap.add_argument("--sky-intensity", type=float, default=1.0)
    ap.add_argument("--sky-rotation", type=float, default=0.0, help="degrees about +Y")
    ap.add_argument("--variant", default="scalar_rgb", help="Mitsuba variant, e.g. llvm_ad_rgb (vectorised)")
    ap.add_argument("--rr-depth", type=int, default=1000, help="Russian roulette from this depth (Mitsuba's default: 5)")
    ap.add_argument("--sampler", default="independent", help="Mitsuba sampler: independent, stratified, multijitter, sobol...")
    a = ap.parse_args()
    select_variant(a.variant)
    scene = build_scene(a.scene, a.width, a.height, a.spp, a.max_bounces, a.sky, a.sky_intensity, a.sky_rotation,
                        a.rr_depth, a.sampler)
    t0 = time.time()
    img = mi.render(scene, spp=a.spp, seed=a.seed)
    import drjit as dr
    dr.eval(img)  # the llvm variants render lazily: evaluate before stopping the clock
    dr.sync_thread()
    dt = time.time() - t0
    mi.Bitmap(img).write(a.out)
    print(f"wrote {a.out} ({a.width}x{a.height}, {a.spp} spp, max_depth {a.max_bounces + 1}, {a.variant}) "
          f"in {dt:.2f} s")


if __name__ == "__main__":
    main()
