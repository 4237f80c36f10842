//! The WebAssembly binding of lrmesh (`web/API.md`): open a container and answer corner
//! queries on its bytes, decode it whole, and (with the `encoder` feature) write one from a
//! mesh file. Thin: every answer comes from the library; this crate only converts ids and
//! arrays for JavaScript.

mod file;

pub use file::LrmFile;
use wasm_bindgen::prelude::*;

/// Opens a container checked well formed (`FORMAT.md` §5.1): corner queries then answer on
/// its bytes; an Edgebreaker file is decoded here.
#[wasm_bindgen]
pub fn open(bytes: Vec<u8>) -> Result<LrmFile, JsError> {
    LrmFile::new(bytes, false)
}

/// [`open`] after every validity rule (`lrmesh verify`).
#[wasm_bindgen(js_name = openVerified)]
pub fn open_verified(bytes: Vec<u8>) -> Result<LrmFile, JsError> {
    LrmFile::new(bytes, true)
}

/// One full decode as `lrmesh decode` does it before writing: every rule checked, then the
/// mesh into arrays; returns the triangle count (so that the work is not optimised away).
/// The page times it (`decodeBench` in `lrmesh.js`): WebAssembly has no clock of its own.
#[wasm_bindgen(js_name = decodeOnce)]
pub fn decode_once(bytes: &[u8]) -> Result<u32, JsError> {
    let file = lrmesh::read::open_verified(bytes, &lrmesh::read::Limits::default())
        .map_err(|e| JsError::new(&e.to_string()))?;
    Ok(file.to_mesh().triangles.len() as u32)
}

/// Whether this build has the encoder (`false` in the decoder-only build).
#[wasm_bindgen(js_name = encoderAvailable)]
pub fn encoder_available() -> bool {
    cfg!(feature = "encoder")
}

/// A container of the mesh in `mesh_bytes` (`format`: obj, ply, off, stl, gltf, glb or lrm),
/// written with `options` (a JSON object: `connectivity`, `quantizePosition`, `level`,
/// `keepOrder`; every key optional), as `lrmesh encode` writes it but for `META`.
#[cfg(feature = "encoder")]
#[wasm_bindgen]
pub fn encode(mesh_bytes: &[u8], format: &str, options: &str) -> Result<Vec<u8>, JsError> {
    let format = mesh_format(format)?;
    let mesh = lrmesh::io::read_mesh_bytes(mesh_bytes, format, &Default::default())
        .map_err(|e| JsError::new(&e.to_string()))?
        .mesh;
    let options = encode_options(options)?;
    lrmesh::write::encode(&mesh, &options).map_err(|e| JsError::new(&e.to_string()))
}

#[cfg(feature = "encoder")]
fn mesh_format(name: &str) -> Result<lrmesh::io::MeshFormat, JsError> {
    use lrmesh::io::MeshFormat;
    Ok(match name.to_ascii_lowercase().as_str() {
        "obj" => MeshFormat::Obj,
        "off" => MeshFormat::Off,
        "ply" => MeshFormat::Ply,
        "stl" => MeshFormat::Stl,
        "gltf" => MeshFormat::Gltf,
        "glb" => MeshFormat::Glb,
        "lrm" => MeshFormat::Lrm,
        other => {
            return Err(JsError::new(&format!(
                "unknown mesh format `{other}`: expected obj, ply, off, stl, gltf, glb or lrm"
            )))
        }
    })
}

/// The connectivity named as on the command line.
#[cfg(feature = "encoder")]
pub(crate) fn connectivity(name: &str) -> Result<lrmesh::write::Connectivity, JsError> {
    use lrmesh::write::Connectivity;
    Ok(match name {
        "lr" => Connectivity::Lr,
        "lr-compact" => Connectivity::LrCompact,
        "zipper" => Connectivity::Zipper,
        "edgebreaker" => Connectivity::Edgebreaker,
        "strips" => Connectivity::Strips,
        other => {
            return Err(JsError::new(&format!(
                "unknown connectivity `{other}`: expected lr, lr-compact, zipper, edgebreaker or strips"
            )))
        }
    })
}

/// The `META` of what the page writes: this binding as the generator.
#[cfg(feature = "encoder")]
pub(crate) fn metadata() -> lrmesh::format::Metadata {
    lrmesh::format::Metadata {
        generator: format!("lrmesh {} (web)", env!("CARGO_PKG_VERSION")),
        ..Default::default()
    }
}

/// The writer's options from the page's JSON (`web/API.md`), the library's defaults for
/// what it leaves out.
#[cfg(feature = "encoder")]
fn encode_options(json: &str) -> Result<lrmesh::write::EncodeOptions, JsError> {
    let value: serde_json::Value = if json.trim().is_empty() {
        serde_json::Value::Null
    } else {
        serde_json::from_str(json).map_err(|e| JsError::new(&format!("options: {e}")))?
    };
    let mut options = lrmesh::write::EncodeOptions {
        metadata: metadata(),
        ..Default::default()
    };
    let number = |key: &str, max: u64| -> Result<Option<u8>, JsError> {
        match value.get(key) {
            None | Some(serde_json::Value::Null) => Ok(None),
            Some(v) => v
                .as_u64()
                .filter(|&n| n <= max)
                .map(|n| Some(n as u8))
                .ok_or_else(|| JsError::new(&format!("options.{key}: an integer up to {max}"))),
        }
    };
    if let Some(name) = value.get("connectivity").and_then(|v| v.as_str()) {
        options.connectivity = connectivity(name)?;
    }
    options.position_bits = number("quantizePosition", 30)?;
    if let Some(level) = number("level", 9)? {
        options.level = level;
    }
    options.keep_order = value
        .get("keepOrder")
        .and_then(|v| v.as_bool())
        .unwrap_or(false);
    Ok(options)
}
