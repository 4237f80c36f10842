//! The glTF JSON document as far as geometry needs it, checked field by field: after
//! [`Document::parse`], every index one object holds into another array is in range, so the
//! rest of the reader indexes those arrays directly.

use serde_json::Value;

use super::json::{index_value, objects, show, Obj};
use super::json_error;
use crate::error::Result;
use crate::mesh::ComponentType;

/// A buffer: its declared length and, unless it is a GLB's BIN chunk, its URI.
pub(super) struct Buffer {
    pub uri: Option<String>,
    pub byte_length: u64,
}

/// A slice of a buffer.
pub(super) struct View {
    pub buffer: usize,
    pub byte_offset: u64,
    pub byte_length: u64,
    pub byte_stride: Option<u64>,
}

/// An accessor's element type: `SCALAR`, `VEC2` to `VEC4`, or a matrix.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum ElementType {
    /// One to four components.
    Vector(u8),
    /// `MAT2`, `MAT3` or `MAT4`: not read as an attribute.
    Matrix(u8),
}

impl ElementType {
    pub fn name(self) -> String {
        match self {
            ElementType::Vector(1) => "SCALAR".to_string(),
            ElementType::Vector(n) => format!("VEC{n}"),
            ElementType::Matrix(n) => format!("MAT{n}"),
        }
    }
}

/// Where a sparse accessor's indices and values are.
pub(super) struct Sparse {
    pub count: u64,
    pub indices_view: usize,
    pub indices_offset: u64,
    pub indices_type: ComponentType,
    pub values_view: usize,
    pub values_offset: u64,
}

/// A typed view of a buffer view.
pub(super) struct Accessor {
    pub view: Option<usize>,
    pub byte_offset: u64,
    pub component: ComponentType,
    pub normalized: bool,
    pub count: u64,
    pub element: ElementType,
    pub sparse: Option<Sparse>,
}

/// One primitive of a mesh.
pub(super) struct Primitive {
    /// Attribute name and accessor, in the file's order.
    pub attributes: Vec<(String, usize)>,
    pub indices: Option<usize>,
    pub material: Option<usize>,
    pub mode: u64,
    /// `extras.group`, where this crate's writer keeps an OBJ group.
    pub group: Option<String>,
    pub has_targets: bool,
}

/// A mesh: named primitives.
pub(super) struct MeshDef {
    pub name: Option<String>,
    pub primitives: Vec<Primitive>,
}

/// A node of the scene graph.
pub(super) struct Node {
    pub name: Option<String>,
    pub mesh: Option<usize>,
    pub children: Vec<usize>,
    /// Local transform, column-major.
    pub local: [f64; 16],
    pub has_skin: bool,
}

/// The parts of the document the reader uses.
pub(super) struct Document {
    pub buffers: Vec<Buffer>,
    pub views: Vec<View>,
    pub accessors: Vec<Accessor>,
    pub meshes: Vec<MeshDef>,
    pub nodes: Vec<Node>,
    /// Root nodes of each scene.
    pub scenes: Vec<Vec<usize>>,
    pub scene: Option<usize>,
    /// Material names (`None` for an unnamed material).
    pub materials: Vec<Option<String>>,
    pub extensions_used: Vec<String>,
    pub extensions_required: Vec<String>,
}

fn component_type(path: &str, code: u64) -> Result<ComponentType> {
    Ok(match code {
        5120 => ComponentType::I8,
        5121 => ComponentType::U8,
        5122 => ComponentType::I16,
        5123 => ComponentType::U16,
        5125 => ComponentType::U32,
        5126 => ComponentType::F32,
        other => {
            return Err(json_error(
                path,
                format!("unknown component type {other} (expected 5120 to 5126, not 5124)"),
            ))
        }
    })
}

impl Document {
    /// Checks the document's structure and every cross-reference.
    ///
    /// # Errors
    /// A parse error naming the JSON path of the first problem.
    pub fn parse(root: &Value) -> Result<Document> {
        let root = Obj::new(root, "the document")?;
        let asset = Obj::new(
            root.map
                .get("asset")
                .ok_or_else(|| json_error("the document", "`asset` is missing: not glTF"))?,
            "asset",
        )?;
        let version = asset
            .string("version")?
            .ok_or_else(|| json_error("asset", "`version` is missing"))?;
        if version.split('.').next() != Some("2") {
            return Err(json_error(
                "asset.version",
                format!(
                    "version `{}`: only glTF 2.x is read",
                    super::escape(version)
                ),
            ));
        }
        let strings = |key: &str| -> Result<Vec<String>> {
            root.array(key)?
                .iter()
                .enumerate()
                .map(|(i, v)| match v {
                    Value::String(s) => Ok(s.clone()),
                    other => Err(json_error(
                        &format!("{key}[{i}]"),
                        format!("expected a string, found {}", show(other)),
                    )),
                })
                .collect()
        };
        let extensions_used = strings("extensionsUsed")?;
        let extensions_required = strings("extensionsRequired")?;

        let mut buffers = Vec::new();
        for (v, path) in objects(&root, "buffers")? {
            let o = Obj::new(v, &path)?;
            buffers.push(Buffer {
                uri: o.string("uri")?.map(str::to_string),
                byte_length: o.required_u64("byteLength")?,
            });
        }
        let mut views = Vec::new();
        for (v, path) in objects(&root, "bufferViews")? {
            let o = Obj::new(v, &path)?;
            views.push(View {
                buffer: o.required_index("buffer", buffers.len(), "buffers")?,
                byte_offset: o.u64("byteOffset")?.unwrap_or(0),
                byte_length: o.required_u64("byteLength")?,
                byte_stride: o.u64("byteStride")?,
            });
        }
        let accessors = objects(&root, "accessors")?
            .iter()
            .map(|(v, path)| parse_accessor(Obj::new(v, path)?, views.len()))
            .collect::<Result<Vec<_>>>()?;
        let mut materials = Vec::new();
        for (v, path) in objects(&root, "materials")? {
            materials.push(Obj::new(v, &path)?.string("name")?.map(str::to_string));
        }
        let meshes = objects(&root, "meshes")?
            .iter()
            .map(|(v, path)| parse_mesh(Obj::new(v, path)?, accessors.len(), materials.len()))
            .collect::<Result<Vec<_>>>()?;
        let node_values = objects(&root, "nodes")?;
        let nodes = node_values
            .iter()
            .map(|(v, path)| parse_node(Obj::new(v, path)?, meshes.len(), node_values.len()))
            .collect::<Result<Vec<_>>>()?;
        let mut scenes = Vec::new();
        for (v, path) in objects(&root, "scenes")? {
            let o = Obj::new(v, &path)?;
            let roots = o
                .array("nodes")?
                .iter()
                .enumerate()
                .map(|(i, v)| index_value(&format!("{path}.nodes[{i}]"), v, nodes.len(), "nodes"))
                .collect::<Result<Vec<_>>>()?;
            scenes.push(roots);
        }
        let scene = root.index("scene", scenes.len(), "scenes")?;
        Ok(Document {
            buffers,
            views,
            accessors,
            meshes,
            nodes,
            scenes,
            scene,
            materials,
            extensions_used,
            extensions_required,
        })
    }
}

fn parse_accessor(o: Obj, views: usize) -> Result<Accessor> {
    let component = component_type(
        &o.field_path("componentType"),
        o.required_u64("componentType")?,
    )?;
    let type_name = o
        .string("type")?
        .ok_or_else(|| json_error(o.path, "`type` is missing"))?;
    let element = match type_name {
        "SCALAR" => ElementType::Vector(1),
        "VEC2" => ElementType::Vector(2),
        "VEC3" => ElementType::Vector(3),
        "VEC4" => ElementType::Vector(4),
        "MAT2" => ElementType::Matrix(2),
        "MAT3" => ElementType::Matrix(3),
        "MAT4" => ElementType::Matrix(4),
        other => {
            return Err(json_error(
                &o.field_path("type"),
                format!("unknown type `{}`", super::escape(other)),
            ))
        }
    };
    let normalized = o.bool("normalized")?;
    if normalized && matches!(component, ComponentType::F32 | ComponentType::U32) {
        return Err(json_error(
            &o.field_path("normalized"),
            "normalized is true for FLOAT or UNSIGNED_INT components, which cannot be normalized",
        ));
    }
    let sparse = match o.map.get("sparse") {
        None => None,
        Some(v) => {
            let path = o.field_path("sparse");
            let s = Obj::new(v, &path)?;
            let ipath = s.field_path("indices");
            let indices = Obj::new(
                s.map
                    .get("indices")
                    .ok_or_else(|| json_error(&path, "`indices` is missing"))?,
                &ipath,
            )?;
            let vpath = s.field_path("values");
            let values = Obj::new(
                s.map
                    .get("values")
                    .ok_or_else(|| json_error(&path, "`values` is missing"))?,
                &vpath,
            )?;
            let indices_type = component_type(
                &indices.field_path("componentType"),
                indices.required_u64("componentType")?,
            )?;
            if !matches!(
                indices_type,
                ComponentType::U8 | ComponentType::U16 | ComponentType::U32
            ) {
                return Err(json_error(
                    &indices.field_path("componentType"),
                    "sparse indices must be unsigned bytes, shorts or ints",
                ));
            }
            Some(Sparse {
                count: s.required_u64("count")?,
                indices_view: indices.required_index("bufferView", views, "bufferViews")?,
                indices_offset: indices.u64("byteOffset")?.unwrap_or(0),
                indices_type,
                values_view: values.required_index("bufferView", views, "bufferViews")?,
                values_offset: values.u64("byteOffset")?.unwrap_or(0),
            })
        }
    };
    Ok(Accessor {
        view: o.index("bufferView", views, "bufferViews")?,
        byte_offset: o.u64("byteOffset")?.unwrap_or(0),
        component,
        normalized,
        count: o.required_u64("count")?,
        element,
        sparse,
    })
}

fn parse_mesh(o: Obj, accessors: usize, materials: usize) -> Result<MeshDef> {
    let mut primitives = Vec::new();
    for (p, v) in o.array("primitives")?.iter().enumerate() {
        let path = format!("{}.primitives[{p}]", o.path);
        let prim = Obj::new(v, &path)?;
        let apath = prim.field_path("attributes");
        let attributes = match prim.map.get("attributes") {
            None => Vec::new(),
            Some(v) => {
                let a = Obj::new(v, &apath)?;
                a.map
                    .iter()
                    .map(|(name, v)| {
                        let path = format!("{apath}.{}", super::escape(name));
                        Ok((name.clone(), index_value(&path, v, accessors, "accessors")?))
                    })
                    .collect::<Result<Vec<_>>>()?
            }
        };
        let group = match prim.map.get("extras") {
            Some(Value::Object(extras)) => match extras.get("group") {
                Some(Value::String(g)) => Some(g.clone()),
                _ => None,
            },
            _ => None,
        };
        primitives.push(Primitive {
            attributes,
            indices: prim.index("indices", accessors, "accessors")?,
            material: prim.index("material", materials, "materials")?,
            mode: prim.u64("mode")?.unwrap_or(4),
            group,
            has_targets: !prim.array("targets")?.is_empty(),
        });
    }
    Ok(MeshDef {
        name: o.string("name")?.map(str::to_string),
        primitives,
    })
}

fn parse_node(o: Obj, meshes: usize, nodes: usize) -> Result<Node> {
    let children = o
        .array("children")?
        .iter()
        .enumerate()
        .map(|(i, v)| index_value(&format!("{}.children[{i}]", o.path), v, nodes, "nodes"))
        .collect::<Result<Vec<_>>>()?;
    let local = match o.numbers("matrix", 16)? {
        Some(m) => std::array::from_fn(|i| m[i]),
        None => {
            let t = o.numbers("translation", 3)?.unwrap_or(vec![0.0; 3]);
            let r = o
                .numbers("rotation", 4)?
                .unwrap_or(vec![0.0, 0.0, 0.0, 1.0]);
            let s = o.numbers("scale", 3)?.unwrap_or(vec![1.0; 3]);
            super::transform::trs(
                [t[0], t[1], t[2]],
                [r[0], r[1], r[2], r[3]],
                [s[0], s[1], s[2]],
            )
            .ok_or_else(|| json_error(&o.field_path("rotation"), "the quaternion is zero"))?
        }
    };
    Ok(Node {
        name: o.string("name")?.map(str::to_string),
        mesh: o.index("mesh", meshes, "meshes")?,
        children,
        local,
        has_skin: o.map.contains_key("skin"),
    })
}
