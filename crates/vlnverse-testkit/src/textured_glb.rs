//! A small textured home built in memory (no shared scene has textures): a 4 m x 4 m floor
//! quad and a 4 m x 2.5 m wall quad at `z = -2`, with texture coordinates and one embedded PNG
//! base-colour texture whose texels all differ. Used by the `vlnverse-import` texture tests and
//! the `vlnverse-sensors` imported-texture renders.

/// Side of the checker texture in texels.
pub const SIDE: u32 = 8;
/// Texture repeats across the floor (the floor's `u` and `v` run from 0 to this).
pub const FLOOR_REPEAT: f32 = 2.0;

/// Texel `(x, y)` (column, row) of the fixture's texture: every texel a different colour.
pub fn texel(x: u32, y: u32) -> [u8; 3] {
    let odd = (x + y) % 2 == 1;
    [
        (16 + 32 * x) as u8,
        (16 + 32 * y) as u8,
        if odd { 220 } else { 40 },
    ]
}

/// The texture as row-major texels.
pub fn texels() -> Vec<[u8; 3]> {
    (0..SIDE)
        .flat_map(|y| (0..SIDE).map(move |x| texel(x, y)))
        .collect()
}

/// PNG bytes of `w x h` RGB texels.
pub fn png(w: u32, h: u32, texels: &[[u8; 3]]) -> Vec<u8> {
    let data: Vec<u8> = texels.iter().flatten().copied().collect();
    let mut out = Vec::new();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut out),
        &data,
        w,
        h,
        image::ExtendedColorType::Rgb8,
    )
    .expect("an RGB8 PNG of matching size encodes into memory");
    out
}

/// Texture coordinates (glTF convention) of a world point on the floor (`y = 0`).
pub fn floor_uv(x: f32, z: f32) -> [f32; 2] {
    [
        (x + 2.0) / 4.0 * FLOOR_REPEAT,
        (z + 2.0) / 4.0 * FLOOR_REPEAT,
    ]
}

/// Texture coordinates of a world point on the wall (`z = -2`, `y` in 0..2.5).
pub fn wall_uv(x: f32, y: f32) -> [f32; 2] {
    [(x + 2.0) / 4.0, (2.5 - y) / 2.5]
}

fn floats(out: &mut Vec<u8>, v: &[f32]) {
    for x in v {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

/// The GLB: nodes `floor` and `wall` (labelled through `extras`), one textured material whose
/// image is `image` (PNG bytes, `mimeType` image/png) in the binary chunk.
pub fn glb(image: &[u8]) -> Vec<u8> {
    let floor: [[f32; 3]; 4] = [
        [-2.0, 0.0, -2.0],
        [2.0, 0.0, -2.0],
        [2.0, 0.0, 2.0],
        [-2.0, 0.0, 2.0],
    ];
    let wall: [[f32; 3]; 4] = [
        [-2.0, 0.0, -2.0],
        [2.0, 0.0, -2.0],
        [2.0, 2.5, -2.0],
        [-2.0, 2.5, -2.0],
    ];
    let floor_uvs: Vec<[f32; 2]> = floor.iter().map(|p| floor_uv(p[0], p[2])).collect();
    let wall_uvs: Vec<[f32; 2]> = wall.iter().map(|p| wall_uv(p[0], p[1])).collect();
    // Floor faces +y, wall faces +z (towards the room).
    let floor_idx: [u32; 6] = [0, 3, 2, 0, 2, 1];
    let wall_idx: [u32; 6] = [0, 1, 2, 0, 2, 3];
    let mut bin = Vec::new();
    // (offset, length) of each buffer view, in accessor order.
    let mut views = Vec::new();
    for (pos, uv, idx) in [
        (&floor, &floor_uvs, &floor_idx),
        (&wall, &wall_uvs, &wall_idx),
    ] {
        let at = bin.len();
        floats(&mut bin, pos.as_flattened());
        views.push((at, bin.len() - at));
        let at = bin.len();
        floats(&mut bin, uv.as_flattened());
        views.push((at, bin.len() - at));
        let at = bin.len();
        for i in idx {
            bin.extend_from_slice(&i.to_le_bytes());
        }
        views.push((at, bin.len() - at));
    }
    let at = bin.len();
    bin.extend_from_slice(image);
    views.push((at, image.len()));
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let view_json: Vec<String> = views
        .iter()
        .map(|(o, l)| format!(r#"{{"buffer":0,"byteOffset":{o},"byteLength":{l}}}"#))
        .collect();
    let mut accessors = Vec::new();
    for (k, (lo, hi)) in [
        ([-2.0, 0.0, -2.0], [2.0, 0.0, 2.0]),
        ([-2.0, 0.0, -2.0], [2.0, 2.5, -2.0]),
    ]
    .iter()
    .enumerate()
    {
        let v = 3 * k;
        accessors.push(format!(
            r#"{{"bufferView":{v},"componentType":5126,"count":4,"type":"VEC3","min":{lo:?},"max":{hi:?}}}"#
        ));
        accessors.push(format!(
            r#"{{"bufferView":{},"componentType":5126,"count":4,"type":"VEC2"}}"#,
            v + 1
        ));
        accessors.push(format!(
            r#"{{"bufferView":{},"componentType":5125,"count":6,"type":"SCALAR"}}"#,
            v + 2
        ));
    }
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,1]}}],
"nodes":[{{"name":"floor","mesh":0,"extras":{{"class":"floor"}}}},{{"name":"wall","mesh":1,"extras":{{"class":"wall"}}}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"indices":2,"material":0}}]}},
{{"primitives":[{{"attributes":{{"POSITION":3,"TEXCOORD_0":4}},"indices":5,"material":0}}]}}],
"materials":[{{"name":"checker","pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}},"metallicFactor":0.0}}}}],
"textures":[{{"source":0}}],
"images":[{{"bufferView":6,"mimeType":"image/png"}}],
"buffers":[{{"byteLength":{}}}],
"bufferViews":[{}],
"accessors":[{}]}}"#,
        bin.len(),
        view_json.join(","),
        accessors.join(",")
    );
    vlnverse_env::io::glb::glb_container(json.as_bytes(), &bin)
}

/// The fixture with its intact checker texture.
pub fn checker_glb() -> Vec<u8> {
    glb(&png(SIDE, SIDE, &texels()))
}
