//! Reading a glTF file: its parts, its document and buffers, then the default scene's mesh
//! instances handed to the [`Builder`] (see the module docs of [`super`] for the rules).

use serde_json::Value;

use super::accessor::Budget;
use super::assemble::Builder;
use super::buffers;
use super::document::Document;
use super::transform::{multiply, Matrix, IDENTITY};
use super::{byte_error, escape, json_error, FORMAT};
use crate::error::{Location, ParseError, Result};
use crate::io::{Loaded, ReadOptions};

/// Extensions that store geometry where this reader does not look.
const UNSUPPORTED: [&str; 4] = [
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_meshopt_compression",
    "EXT_mesh_gpu_instancing",
];

/// Reads a whole file (see [`super::read_with`]).
pub(super) fn read(
    bytes: &[u8],
    opts: &ReadOptions,
    external: &mut dyn FnMut(&str) -> std::result::Result<Vec<u8>, String>,
) -> Result<Loaded> {
    let parts = buffers::split(bytes)?;
    let root: Value = serde_json::from_slice(parts.json).map_err(|e| {
        if parts.bin.is_some() || parts.json_offset > 3 {
            byte_error(parts.json_offset, format!("JSON chunk: invalid JSON: {e}"))
        } else {
            ParseError::new(
                FORMAT,
                Location::Line(e.line() as u64),
                format!("invalid JSON: {e}"),
            )
            .into()
        }
    })?;
    let doc = Document::parse(&root)?;
    drop(root);
    let mut warnings = Vec::new();
    for (i, name) in doc.extensions_required.iter().enumerate() {
        if UNSUPPORTED.contains(&name.as_str()) {
            return Err(json_error(
                &format!("extensionsRequired[{i}]"),
                format!("`{name}` stores geometry in a way this reader does not read"),
            ));
        }
        if name != "KHR_mesh_quantization" && !name.starts_with("KHR_materials_") {
            warnings.push(format!(
                "extensionsRequired lists `{}`, which this reader does not know; ignored",
                escape(name)
            ));
        }
    }
    let bufs = buffers::load(&doc, parts.bin, external)?;
    let budget = Budget::new((bytes.len() as u64).saturating_add(bufs.external_bytes));
    let mut builder = Builder::new(&doc, &bufs, budget);
    for instance in instances(&doc)? {
        builder.add_instance(&instance)?;
    }
    let mut mesh = builder.finish(&mut warnings)?;
    if opts.weld {
        mesh = mesh.weld();
    }
    Ok(Loaded { mesh, warnings })
}

/// A mesh placed by a node.
pub(super) struct Instance {
    pub node: Option<usize>,
    pub mesh: usize,
    pub world: Matrix,
}

/// The mesh instances of the default scene, depth first in the order of the scene's and
/// nodes' lists.
fn instances(doc: &Document) -> Result<Vec<Instance>> {
    let (roots, path) = match doc.scene.or((!doc.scenes.is_empty()).then_some(0)) {
        Some(s) => (doc.scenes[s].clone(), format!("scenes[{s}]")),
        None if doc.nodes.is_empty() => {
            return Ok((0..doc.meshes.len())
                .map(|mesh| Instance {
                    node: None,
                    mesh,
                    world: IDENTITY,
                })
                .collect())
        }
        None => {
            let mut is_child = vec![false; doc.nodes.len()];
            for n in &doc.nodes {
                for &c in &n.children {
                    is_child[c] = true;
                }
            }
            let roots = (0..doc.nodes.len()).filter(|&n| !is_child[n]).collect();
            (roots, "the root nodes".to_string())
        }
    };
    let mut visited = vec![false; doc.nodes.len()];
    let mut out = Vec::new();
    let mut stack: Vec<(usize, Matrix)> = roots.iter().rev().map(|&n| (n, IDENTITY)).collect();
    while let Some((n, parent)) = stack.pop() {
        if std::mem::replace(&mut visited[n], true) {
            return Err(json_error(
                &format!("nodes[{n}]"),
                format!(
                    "reached twice from {path}: a node has at most one parent and the graph \
                     has no cycle"
                ),
            ));
        }
        let node = &doc.nodes[n];
        let world = multiply(&parent, &node.local);
        if let Some(mesh) = node.mesh {
            out.push(Instance {
                node: Some(n),
                mesh,
                world,
            });
        }
        stack.extend(node.children.iter().rev().map(|&c| (c, world)));
    }
    Ok(out)
}
