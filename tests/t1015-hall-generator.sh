#!/bin/sh
test_description='doc/examples/hall: the generator reproduces the committed glTF and OBJ, which are valid and agree'
. "$srcdir/tests/lib.sh"

# The example level (doc/examples/hall.scene) is hall.gltf and hall.obj,
# both written by doc/examples/hall-gen.py.  No tool reads them here:
# this checks the files themselves, as glTF 2.0 says they must be and as
# the layout the scene's comments describe.

examples="$srcdir/doc/examples"
files="hall.gltf hall.bin hall.obj hall.mtl hall-textures/plaster.png hall-textures/tiles.png"

PY=
for p in "${PYTHON3:-}" /usr/bin/python3 python3
do
	test -n "$p" && command -v "$p" >/dev/null 2>&1 && { PY=$p; break; }
done

# check.py DIR: the glTF in DIR against the specification's rules, then
# the OBJ against the glTF's world-space triangles.  Prints what it
# measured; exits 1 with a line per fault.
cat >check.py <<'PYEOF'
import json, math, os, struct, sys

d = sys.argv[1]
faults = []


def fault(msg):
    faults.append(msg)


g = json.load(open(os.path.join(d, "hall.gltf")))
binary = open(os.path.join(d, "hall.bin"), "rb").read()

if g.get("asset", {}).get("version") != "2.0":
    fault("asset.version is not 2.0")

# buffers and views
bufs = g["buffers"]
if len(bufs) != 1 or bufs[0].get("uri") != "hall.bin":
    fault("expected one buffer, hall.bin")
if bufs[0]["byteLength"] != len(binary):
    fault("buffer byteLength %d, hall.bin holds %d" % (bufs[0]["byteLength"], len(binary)))
for k, v in enumerate(g["bufferViews"]):
    off = v.get("byteOffset", 0)
    if v["buffer"] != 0 or off + v["byteLength"] > bufs[0]["byteLength"]:
        fault("bufferView %d is outside its buffer" % k)
    if off % 4:
        fault("bufferView %d starts at %d, not 4-aligned" % (k, off))
    if v.get("target") not in (34962, 34963):
        fault("bufferView %d: target %s" % (k, v.get("target")))
    s = v.get("byteStride")
    if s is not None and (v.get("target") == 34963 or s % 4 or not 4 <= s <= 252):
        fault("bufferView %d: byteStride %s" % (k, s))

# accessors: in their views, aligned, read
CSIZE = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}
CFMT = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
data = []
for k, a in enumerate(g["accessors"]):
    v = g["bufferViews"][a["bufferView"]]
    cs, n = CSIZE[a["componentType"]], NCOMP[a["type"]]
    elem = cs * n
    stride = v.get("byteStride", elem)
    start = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    if start % cs or stride % cs:
        fault("accessor %d is not aligned to its component size" % k)
    if a["count"] < 1 or a.get("byteOffset", 0) + stride * (a["count"] - 1) + elem > v["byteLength"]:
        fault("accessor %d runs past its bufferView" % k)
        data.append(None)
        continue
    rows = [struct.unpack_from("<%d%s" % (n, CFMT[a["componentType"]]), binary, start + i * stride)
            for i in range(a["count"])]
    data.append(rows)
    if ("min" in a) != ("max" in a):
        fault("accessor %d has only one of min and max" % k)
    if "min" in a:
        lo = [min(r[c] for r in rows) for c in range(n)]
        hi = [max(r[c] for r in rows) for c in range(n)]
        if lo != a["min"] or hi != a["max"]:
            fault("accessor %d: min %s max %s, the data's are %s %s" % (k, a["min"], a["max"], lo, hi))


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


# materials, textures, images
nmat = len(g["materials"])
for k, t in enumerate(g["textures"]):
    if not 0 <= t["source"] < len(g["images"]) or not 0 <= t["sampler"] < len(g["samplers"]):
        fault("texture %d: bad source or sampler" % k)
for k, im in enumerate(g["images"]):
    p = os.path.join(d, im["uri"])
    if not os.path.isfile(p) or open(p, "rb").read(8) != b"\x89PNG\r\n\x1a\n":
        fault("image %d: %s is not a PNG beside the glTF" % (k, im["uri"]))
mirrors = []
used_ext = set()
for k, m in enumerate(g["materials"]):
    pbr = m.get("pbrMetallicRoughness", {})
    info = pbr.get("baseColorTexture")
    if info:
        if not 0 <= info["index"] < len(g["textures"]):
            fault("material %d: texture %d" % (k, info["index"]))
        used_ext.update(info.get("extensions", {}))
    for f in pbr.get("baseColorFactor", [1] * 4) + m.get("emissiveFactor", [0] * 3):
        if not 0 <= f <= 1:
            fault("material %d: factor %s outside [0, 1]" % (k, f))
    used_ext.update(m.get("extensions", {}))
    if m.get("emissiveFactor") and m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] <= 1:
        fault("material %d emits without KHR_materials_emissive_strength" % k)
    if m.get("extras", {}).get("reflect", {}).get("mirror") is True:
        mirrors.append(m["name"])
print("materials", nmat, "mirror", " ".join(mirrors))
if len(mirrors) != 1 or not mirrors[0].startswith("mirror"):
    fault("expected one mirror material named mirror...: %s" % mirrors)

# meshes
ntri = {}
for k, mesh in enumerate(g["meshes"]):
    ntri[k] = 0
    for p in mesh["primitives"]:
        at = p["attributes"]
        acc = g["accessors"]
        pos, nrm, uv = (data[at[s]] for s in ("POSITION", "NORMAL", "TEXCOORD_0"))
        if pos is None or nrm is None or uv is None:
            continue
        if "min" not in acc[at["POSITION"]]:
            fault("mesh %d: POSITION without min and max" % k)
        for s, kind in (("POSITION", "VEC3"), ("NORMAL", "VEC3"), ("TEXCOORD_0", "VEC2")):
            if acc[at[s]]["type"] != kind or acc[at[s]]["componentType"] != 5126:
                fault("mesh %d: %s is not float %s" % (k, s, kind))
        if not len(pos) == len(nrm) == len(uv):
            fault("mesh %d: attribute counts differ" % k)
        for n in nrm:
            if abs(math.sqrt(dot(n, n)) - 1) > 1e-5:
                fault("mesh %d: normal %s is not unit" % (k, n))
                break
        if p.get("mode", 4) != 4 or not 0 <= p.get("material", -1) < nmat:
            fault("mesh %d: mode or material index" % k)
        ia = acc[p["indices"]]
        idx = data[p["indices"]]
        if ia["componentType"] not in (5123, 5125) or ia["type"] != "SCALAR" or idx is None:
            fault("mesh %d: indices not unsigned short or int scalars" % k)
            continue
        idx = [r[0] for r in idx]
        if len(idx) % 3 or max(idx) >= len(pos):
            fault("mesh %d: indices out of range" % k)
            continue
        for t in range(0, len(idx), 3):
            a, b, c = (pos[i] for i in idx[t:t + 3])
            gn = cross(sub(b, a), sub(c, a))
            if math.sqrt(dot(gn, gn)) / 2 < 1e-5:
                fault("mesh %d: triangle %d is degenerate" % (k, t // 3))
            elif dot(gn, [sum(nrm[i][j] for i in idx[t:t + 3]) for j in range(3)]) <= 0:
                fault("mesh %d: triangle %d winds against its normals" % (k, t // 3))
        ntri[k] += len(idx) // 3

# lights
if "KHR_lights_punctual" in g.get("extensions", {}):
    used_ext.add("KHR_lights_punctual")
lights = g["extensions"]["KHR_lights_punctual"]["lights"]
for k, l in enumerate(lights):
    if l.get("type") not in ("point", "spot", "directional"):
        fault("light %d: type %s" % (k, l.get("type")))
    c = l.get("color", [1, 1, 1])
    if len(c) != 3 or not all(0 <= x <= 1 for x in c) or not l.get("intensity", 1) > 0:
        fault("light %d: color or intensity" % k)
    if "range" in l and not (l["range"] > 0 and l["type"] != "directional"):
        fault("light %d: range" % k)
    if l["type"] == "spot":
        s = l.get("spot")
        if s is None or not 0 <= s.get("innerConeAngle", 0) < s["outerConeAngle"] <= math.pi / 2:
            fault("light %d: spot cone angles" % k)
    elif "spot" in l:
        fault("light %d: spot fields on a %s light" % (k, l["type"]))
print("lights", " ".join(l["type"] for l in lights))
if set(g.get("extensionsUsed", [])) != used_ext:
    fault("extensionsUsed %s, the file uses %s" % (g.get("extensionsUsed"), sorted(used_ext)))

# nodes: a tree under the scene's roots, with unit rotations; world
# transforms as glTF composes them (parent * T * R * S)


def trs(node):
    if "matrix" in node:
        m = node["matrix"]
        return [[m[c * 4 + r] for c in range(4)] for r in range(4)]
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    if abs(x * x + y * y + z * z + w * w - 1) > 1e-6:
        fault("node %s: rotation is not a unit quaternion" % node.get("name"))
    sx, sy, sz = node.get("scale", [1, 1, 1])
    tx, ty, tz = node.get("translation", [0, 0, 0])
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [[r[0][0] * sx, r[0][1] * sy, r[0][2] * sz, tx],
            [r[1][0] * sx, r[1][1] * sy, r[1][2] * sz, ty],
            [r[2][0] * sx, r[2][1] * sy, r[2][2] * sz, tz], [0, 0, 0, 1]]


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def xf(m, p, w=1):
    return [m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] * w for i in range(3)]


world = []   # world-space positions of every triangle's vertices
world_tris = 0
light_at = []
seen = set()
by_name = {}


def walk(k, parent, depth):
    global world_tris
    if k in seen or not 0 <= k < len(g["nodes"]):
        fault("node %d is not in a tree" % k)
        return
    seen.add(k)
    node = g["nodes"][k]
    m = mul(parent, trs(node))
    by_name[node.get("name")] = m
    if "mesh" in node:
        if not 0 <= node["mesh"] < len(g["meshes"]):
            fault("node %d: mesh %d" % (k, node["mesh"]))
            return
        for p in g["meshes"][node["mesh"]]["primitives"]:
            pos = data[p["attributes"]["POSITION"]]
            for i in data[p["indices"]]:
                world.append(tuple(xf(m, pos[i[0]])))
        world_tris += ntri[node["mesh"]]
    lp = node.get("extensions", {}).get("KHR_lights_punctual")
    if lp:
        if not 0 <= lp["light"] < len(lights):
            fault("node %d: light %d" % (k, lp["light"]))
        else:
            light_at.append((lights[lp["light"]]["type"], xf(m, [0, 0, 0]), xf(m, [0, 0, -1], 0)))
    for c in node.get("children", []):
        walk(c, m, depth + 1)


eye = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
for r in g["scenes"][g.get("scene", 0)]["nodes"]:
    walk(r, eye, 0)
held = sorted(n["extensions"]["KHR_lights_punctual"]["light"] for n in g["nodes"]
              if "KHR_lights_punctual" in n.get("extensions", {}))
if held != list(range(len(lights))):
    fault("lights held by the nodes: %s, not each of the %d once" % (held, len(lights)))
if len(seen) != len(g["nodes"]):
    fault("%d nodes are not under the scene" % (len(g["nodes"]) - len(seen)))
if not any(n.get("rotation") and n.get("mesh") is not None and n.get("translation")
           for n in g["nodes"]):
    fault("no node both turns and moves a mesh")
print("nodes", len(g["nodes"]), "meshes", len(g["meshes"]), "triangles", world_tris)

# the layout: the L-shaped hall's bounds, lights where they belong
lo = [min(p[c] for p in world) for c in range(3)]
hi = [max(p[c] for p in world) for c in range(3)]
print("bounds %.3f %.3f %.3f %.3f %.3f %.3f" % tuple(lo + hi))
for t, at, towards in light_at:
    print("light %s at %.3f %.3f %.3f towards %.3f %.3f %.3f" % ((t,) + tuple(at) + tuple(towards)))

# the OBJ: the same triangles, the same world-space positions as a set
v, tris, mtls, mtl_defined, maps = [], 0, set(), set(), []
fv = set()
for line in open(os.path.join(d, "hall.obj")):
    w = line.split()
    if not w:
        continue
    if w[0] == "v":
        v.append(tuple(float(x) for x in w[1:4]))
    elif w[0] == "f":
        if len(w) != 4:
            fault("hall.obj: a face of %d corners" % (len(w) - 1))
        for c in w[1:]:
            fv.add(int(c.split("/")[0]) - 1)
        tris += 1
    elif w[0] == "usemtl":
        mtls.add(w[1])
for line in open(os.path.join(d, "hall.mtl")):
    w = line.split()
    if w and w[0] == "newmtl":
        mtl_defined.add(w[1])
    elif w and w[0].startswith("map_"):
        if not os.path.isfile(os.path.join(d, w[-1])):
            fault("hall.mtl: no file %s" % w[-1])
if mtls - mtl_defined:
    fault("hall.obj uses materials hall.mtl lacks: %s" % sorted(mtls - mtl_defined))
if mtls != {m["name"] for m in g["materials"]}:
    fault("hall.obj's materials differ from hall.gltf's")
print("obj triangles", tris)
if tris != world_tris:
    fault("hall.obj has %d triangles, hall.gltf %d" % (tris, world_tris))
objpos = [v[i] for i in sorted(fv)]

TOL = 1e-4


def grid(points):
    cells = {}
    for p in points:
        cells.setdefault(tuple(int(math.floor(c / 1e-3)) for c in p), []).append(p)
    return cells


def near(cells, p):
    k = [int(math.floor(c / 1e-3)) for c in p]
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for dz in (-1, 0, 1):
                for q in cells.get((k[0] + dx, k[1] + dy, k[2] + dz), ()):
                    if max(abs(q[i] - p[i]) for i in range(3)) <= TOL:
                        return True
    return False


gw, go = grid(world), grid(objpos)
miss = [p for p in set(world) if not near(go, p)]
extra = [p for p in objpos if not near(gw, p)]
if miss:
    fault("%d glTF positions are not in hall.obj, e.g. %s" % (len(miss), sorted(miss)[0]))
if extra:
    fault("%d hall.obj positions are not in hall.gltf, e.g. %s" % (len(extra), sorted(extra)[0]))
if len(v) != len(fv):
    fault("hall.obj has %d positions no face uses" % (len(v) - len(fv)))

for f in faults:
    print("fault:", f, file=sys.stderr)
sys.exit(1 if faults else 0)
PYEOF

if test -z "$PY"
then
	test_skip 'the generator writes the committed files, byte for byte' 'no python3'
	test_skip 'the committed glTF and OBJ are valid and agree' 'no python3'
	test_skip 'the checks find a broken file' 'no python3'
	test_done
fi

test_expect_success 'the generator writes the committed files, byte for byte' '
	mkdir one two &&
	$PY "$examples/hall-gen.py" one &&
	$PY "$examples/hall-gen.py" two &&
	(cd one && find . -type f | sort) >written &&
	for f in $files
	do
		echo "./$f" || return 1
	done | sort >expect &&
	cmp expect written &&
	for f in $files
	do
		cmp "$examples/$f" "one/$f" &&
		cmp one/$f two/$f || return 1
	done
'

# The layout as hall.scene describes it: the main wing x -6 .. 6,
# z -3 .. 3; the side wing x 0 .. 6 up to z 11.4; the windows' panes
# 0.3 m behind the walls; 4.5 m high.  The sun goes down and into the
# hall through the -z windows, the lamp's spot points straight down
# over the table (centred at x 1, z 1, its 30-degree turn leaving the
# lamp where it is), the sconces stand 0.25 m off the side wing's walls.
test_expect_success 'the committed glTF and OBJ are valid and agree' '
	$PY check.py "$examples" >out &&
	cat >expect <<-\EOF &&
	materials 8 mirror mirror-floor
	lights directional spot point point
	nodes 15 meshes 5 triangles 638
	bounds -6.000 0.000 -3.300 6.300 4.500 11.700
	light spot at 1.000 2.880 1.000 towards 0.000 -1.000 0.000
	light directional at 0.000 6.000 -8.000 towards 0.350 -0.549 0.759
	light point at 0.250 2.200 7.400 towards 0.000 0.000 -1.000
	light point at 5.750 2.200 7.400 towards -0.000 0.000 1.000
	obj triangles 638
	EOF
	test_cmp_numbers expect out 0.0005
'

# spoil.py WHAT: breaks the copy here: "byte" changes the fourth byte of
# hall.bin, the first position's x, from -6 to -24; "normal" makes the
# first normal 0.1 % longer.
cat >spoil.py <<'PYEOF'
import json, struct, sys
g = json.load(open("hall.gltf"))
b = bytearray(open("hall.bin", "rb").read())
if sys.argv[1] == "byte":
    b[3] ^= 0x01
else:
    a = g["accessors"][g["meshes"][0]["primitives"][0]["attributes"]["NORMAL"]]
    off = g["bufferViews"][a["bufferView"]]["byteOffset"]
    n = struct.unpack_from("<3f", b, off)
    struct.pack_into("<3f", b, off, *(c * 1.001 for c in n))
open("hall.bin", "wb").write(b)
PYEOF

# The checks are only worth their failures: a byte of a position, a
# buffer one byte longer, a normal made longer, one triangle less in
# the OBJ.
test_expect_success 'the checks find a broken file' '
	cp -R "$examples/hall-textures" "$examples"/hall.* . &&
	chmod -R u+w . &&
	cp hall.bin good.bin &&
	$PY check.py . >out &&
	$PY spoil.py byte &&
	! cmp -s hall.bin good.bin &&
	test_expect_code 1 $PY check.py . >out 2>err &&
	test_grep "^fault: accessor 0: min \[-6.0, 0.0, -3.0\] .* the data.s are \[-24.0, 0.0, -3.0\]" err &&
	test_grep "^fault: 1 glTF positions are not in hall.obj" err &&
	cp good.bin hall.bin &&
	head -c 1 /dev/zero >>hall.bin &&
	test_expect_code 1 $PY check.py . >out 2>err &&
	test_grep "^fault: buffer byteLength [0-9]*, hall.bin holds" err &&
	cp good.bin hall.bin &&
	$PY spoil.py normal &&
	test_expect_code 1 $PY check.py . >out 2>err &&
	test_grep "^fault: mesh 0: normal .* is not unit" err &&
	cp good.bin hall.bin &&
	sed "\$d" hall.obj >short.obj &&
	mv short.obj hall.obj &&
	test_expect_code 1 $PY check.py . >out 2>err &&
	test_grep "^fault: hall.obj has 637 triangles, hall.gltf 638" err
'

test_done
