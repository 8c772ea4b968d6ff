#!/bin/sh
test_description='mesh statements with bad files: each refused in one line naming the scene line and the mesh file'
. "$srcdir/tests/lib.sh"

SQ="'"
# The quad of tests/unit/test-mesh.c (z = 0, facing +Z, 2 x 2): 4
# positions, 4 uv, 6 uint16 indices, 92 bytes; and the same with a NaN
# for the third vertex's x.
QUAD=AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAAAAAAAAAAgD8AAIA/AACAPwAAgD8AAAAAAAAAAAAAAAAAAAEAAgAAAAIAAwA=
NANQUAD=AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAADAfwAAgD8AAAAAAACAvwAAgD8AAAAAAAAAAAAAgD8AAIA/AACAPwAAgD8AAAAAAAAAAAAAAAAAAAEAAgAAAAIAAwA=

# gltf_quad BUFFER-JSON [MATERIAL-JSON [MORE-JSON]]: the quad's .gltf on
# stdout, its buffer as given.
gltf_quad () {
	printf '{"asset":{"version":"2.0"},"buffers":[%s],' "$1" &&
	printf '"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},' &&
	printf '{"buffer":0,"byteOffset":48,"byteLength":32},' &&
	printf '{"buffer":0,"byteOffset":80,"byteLength":12}],' &&
	printf '"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},' &&
	printf '{"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},' &&
	printf '{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}],' &&
	printf '"materials":[%s],' "${2:-{\"name\":\"plain\"\}}" &&
	printf '"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},' &&
	printf '"indices":2,"material":0}]}],' &&
	printf '"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0%s}\n' "${3:-}"
}

data_uri () {
	printf '{"byteLength":92,"uri":"data:application/octet-stream;base64,%s"}' "$1"
}

# bad_mesh 'MESSAGE' <scene: reflect-gbuffer refuses it with status 1,
# one line "reflect-gbuffer: bad.scene:2:6: MESSAGE", nothing on stdout,
# within 10 s and 1.5 GB of address space (none under the sanitizers).
limit=1500000
grep -q fsanitize "$builddir/Makefile" && limit=unlimited
bad_mesh () {
	cat >bad.scene &&
	(ulimit -v $limit && exec timeout 10 reflect-gbuffer -x 8 -y 8 bad.scene) >out 2>err
	test $? -eq 1 &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "^reflect-gbuffer: bad.scene:2:6: $1" err &&
	test ! -s out
}

test_expect_success 'a good quad loads (the files below differ in one thing)' '
	gltf_quad "$(data_uri $QUAD)" >quad.gltf &&
	printf "probe box -3 -3 -3 3 3 3\nmesh quad.gltf\n" >good.scene &&
	reflect-gbuffer -x 8 -y 8 good.scene >out 2>err &&
	test ! -s err && test -s out
'

test_expect_success 'a missing file' '
	bad_mesh "cannot open ${SQ}nope.gltf${SQ}: No such file or directory$" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh nope.gltf
	EOF
'

test_expect_success 'a file that is not a mesh' '
	echo "not a mesh at all" >junk.gltf &&
	bad_mesh "${SQ}junk.gltf${SQ}: not a glTF 2.0 file (its JSON does not parse near byte 0)$" <<-\EOF &&
	probe box -3 -3 -3 3 3 3
	mesh junk.gltf
	EOF
	printf "\211PNG\r\n\032\n\000\000\000\015IHDR" >junk.obj &&
	bad_mesh "${SQ}junk.obj${SQ}: " <<-\EOF &&
	probe box -3 -3 -3 3 3 3
	mesh junk.obj
	EOF
	bad_mesh "${SQ}quad.stl${SQ}: expected a glTF 2.0 (.gltf, .glb) or Wavefront OBJ (.obj) file$" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh quad.stl
	EOF
'

test_expect_success 'a missing texture' '
	gltf_quad "$(data_uri $QUAD)" \
		"{\"name\":\"painted\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}" \
		",\"images\":[{\"uri\":\"gone.png\"}],\"textures\":[{\"source\":0}]" >tex.gltf &&
	bad_mesh "${SQ}tex.gltf${SQ}: material ${SQ}painted${SQ}: .*${SQ}gone.png${SQ}" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh tex.gltf
	EOF
'

test_expect_success 'a missing material library' '
	printf "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n" >nomtl.obj &&
	bad_mesh "${SQ}nomtl.obj${SQ}: cannot open its material library ${SQ}gone.mtl${SQ}: No such file or directory$" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh nomtl.obj
	EOF
'

test_expect_success 'a vertex that is not a number' '
	gltf_quad "$(data_uri $NANQUAD)" >nan.gltf &&
	bad_mesh "${SQ}nan.gltf${SQ}: vertex 2 of mesh .* is not a finite point (nan 1 0)$" <<-\EOF &&
	probe box -3 -3 -3 3 3 3
	mesh nan.gltf
	EOF
	printf "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n" >nan.obj &&
	bad_mesh "${SQ}nan.obj${SQ}: vertex . of mesh .* is not a finite point" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh nan.obj
	EOF
'

test_expect_success 'a buffer claiming 10 GB: refused before any allocation' '
	echo "$QUAD" | base64 -d >small.bin &&
	test $(wc -c <small.bin) -eq 92 &&
	gltf_quad "{\"byteLength\":10737418240,\"uri\":\"small.bin\"}" >big.gltf &&
	bad_mesh "${SQ}big.gltf${SQ}: buffer 0 claims 10737418240 bytes, but its file holds 92$" <<-\EOF &&
	probe box -3 -3 -3 3 3 3
	mesh big.gltf
	EOF
	gltf_quad "{\"byteLength\":10737418240}" >big.json &&
	# a .glb: its JSON chunk padded to 4 bytes, then the 92-byte BIN chunk
	while test $(($(wc -c <big.json) % 4)) -ne 0
	do
		printf " " >>big.json || return 1
	done &&
	le32 () {
		printf "$(printf "\\\\%03o\\\\%03o\\\\%03o\\\\%03o" $(($1 & 255)) \
			$(($1 >> 8 & 255)) $(($1 >> 16 & 255)) $(($1 >> 24 & 255)))"
	} &&
	n=$(wc -c <big.json) &&
	{
		printf glTF && le32 2 && le32 $((12 + 8 + n + 8 + 92)) &&
		le32 $n && printf JSON && cat big.json &&
		le32 92 && printf "BIN\000" && cat small.bin
	} >big.glb &&
	test $(wc -c <big.glb) -eq $((12 + 8 + n + 8 + 92)) &&
	bad_mesh "${SQ}big.glb${SQ}: buffer 0 claims 10737418240 bytes, but the .glb${SQ}s BIN chunk holds 92$" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh big.glb
	EOF
'

test_expect_success 'a byteLength past 2^64, and one not whole: not valid' '
	for len in 1e20 18446744073709551616 1e400 92.5 -92
	do
		gltf_quad "{\"byteLength\":$len,\"uri\":\"small.bin\"}" >huge.gltf &&
		bad_mesh "${SQ}huge.gltf${SQ}: buffer 0 has no valid byteLength$" <<-\EOF || return 1
		probe box -3 -3 -3 3 3 3
		mesh huge.gltf
		EOF
	done
'

test_expect_success 'an accessor claiming more than its bufferView' '
	gltf_quad "$(data_uri $QUAD)" | sed "s/\"count\":4,\"type\":\"VEC3\"/\"count\":1000000000,\"type\":\"VEC3\"/" >count.gltf &&
	bad_mesh "${SQ}count.gltf${SQ}: accessor 0 claims count 1000000000, more than the byteLength of its bufferView (48)$" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh count.gltf
	EOF
'

test_expect_success 'a mesh with no triangles' '
	printf "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n" >lines.obj &&
	bad_mesh "${SQ}lines.obj${SQ}: no triangles (a mesh statement needs surfaces; points and lines are not drawn)$" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh lines.obj
	EOF
'

test_expect_success 'an unknown attribute, a material the file lacks' '
	cat >bad.scene <<-\EOF &&
	probe box -3 -3 -3 3 3 3
	mesh quad.gltf translate 0 1 0 spin 90
	EOF
	test_expect_code 1 reflect-gbuffer -x 8 -y 8 bad.scene >out 2>err &&
	test_one_line_message reflect-gbuffer err &&
	test_grep "^reflect-gbuffer: bad.scene:2:32: unknown mesh attribute .spin. (expected translate, rotate, scale, matrix, roughness, smoothness, metallic, albedo, emission, reflective or material NAME)$" err &&
	bad_mesh "${SQ}quad.gltf${SQ} has no material ${SQ}brass${SQ} (it has ${SQ}plain${SQ})$" <<-\EOF
	probe box -3 -3 -3 3 3 3
	mesh quad.gltf material brass roughness 0.2
	EOF
'

test_done
