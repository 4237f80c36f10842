//! Attributes of a mesh beyond its positions: normals, texture coordinates, colors and named
//! custom ones, each bound per vertex or per corner.

use std::fmt;

/// What an attribute means. At most one attribute of a mesh has a given semantic.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Semantic {
    /// Normals: three components.
    Normal,
    /// Texture coordinates of set `n` (glTF `TEXCOORD_n`): two components.
    TexCoord(u8),
    /// Colors of set `n` (glTF `COLOR_n`): RGB or RGBA.
    Color(u8),
    /// Anything else, by name (glTF `_NAME`, a PLY property): one to four components.
    Custom(String),
}

impl Semantic {
    /// The component counts this semantic allows.
    pub fn allowed_components(&self) -> &'static [u8] {
        match self {
            Semantic::Normal => &[3],
            Semantic::TexCoord(_) => &[2],
            Semantic::Color(_) => &[3, 4],
            Semantic::Custom(_) => &[1, 2, 3, 4],
        }
    }
}

impl fmt::Display for Semantic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Semantic::Normal => write!(f, "normal"),
            Semantic::TexCoord(n) => write!(f, "texcoord{n}"),
            Semantic::Color(n) => write!(f, "color{n}"),
            Semantic::Custom(name) => write!(f, "custom \"{}\"", name.escape_debug()),
        }
    }
}

/// The stored values, flat: `components` numbers per value. The component types are glTF's.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// Signed bytes.
    I8(Vec<i8>),
    /// Unsigned bytes.
    U8(Vec<u8>),
    /// Signed 16-bit integers.
    I16(Vec<i16>),
    /// Unsigned 16-bit integers.
    U16(Vec<u16>),
    /// Unsigned 32-bit integers.
    U32(Vec<u32>),
    /// Binary32 floats.
    F32(Vec<f32>),
}

/// The type of one component, with its code in the container (FORMAT.md §3.9).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ComponentType {
    /// `i8`, code 1.
    I8 = 1,
    /// `u8`, code 2.
    U8 = 2,
    /// `i16`, code 3.
    I16 = 3,
    /// `u16`, code 4.
    U16 = 4,
    /// `u32`, code 5.
    U32 = 5,
    /// `f32`, code 6.
    F32 = 6,
}

impl ComponentType {
    /// The type of container code `code`, if there is one.
    pub fn from_code(code: u8) -> Option<ComponentType> {
        use ComponentType::*;
        [I8, U8, I16, U16, U32, F32]
            .into_iter()
            .find(|t| *t as u8 == code)
    }

    /// Bytes per component.
    pub fn size(self) -> usize {
        match self {
            ComponentType::I8 | ComponentType::U8 => 1,
            ComponentType::I16 | ComponentType::U16 => 2,
            ComponentType::U32 | ComponentType::F32 => 4,
        }
    }

    /// `x`, a component of this type, as f32: as it is, or, `normalized`, mapped to a
    /// fraction as glTF maps it (`max(x / (2^(n−1) − 1), −1)` signed, `x / (2^n − 1)`
    /// unsigned).
    pub fn to_f32(self, x: f64, normalized: bool) -> f32 {
        if !normalized {
            return x as f32;
        }
        match self {
            ComponentType::I8 => (x / 127.0).max(-1.0) as f32,
            ComponentType::U8 => (x / 255.0) as f32,
            ComponentType::I16 => (x / 32767.0).max(-1.0) as f32,
            ComponentType::U16 => (x / 65535.0) as f32,
            ComponentType::U32 => (x / 4294967295.0) as f32,
            ComponentType::F32 => x as f32,
        }
    }

    /// Whether integers of this type may be normalized (mapped to [0, 1] or [−1, 1]).
    pub fn is_integer(self) -> bool {
        self != ComponentType::F32
    }
}

macro_rules! each_values {
    ($values:expr, $v:ident => $body:expr) => {
        match $values {
            Values::I8($v) => $body,
            Values::U8($v) => $body,
            Values::I16($v) => $body,
            Values::U16($v) => $body,
            Values::U32($v) => $body,
            Values::F32($v) => $body,
        }
    };
}

impl Values {
    /// The component type.
    pub fn component_type(&self) -> ComponentType {
        match self {
            Values::I8(_) => ComponentType::I8,
            Values::U8(_) => ComponentType::U8,
            Values::I16(_) => ComponentType::I16,
            Values::U16(_) => ComponentType::U16,
            Values::U32(_) => ComponentType::U32,
            Values::F32(_) => ComponentType::F32,
        }
    }

    /// Number of components stored (values times components).
    pub fn len(&self) -> usize {
        each_values!(self, v => v.len())
    }

    /// Whether nothing is stored.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// No values of `kind`, with room for `capacity` components.
    pub fn with_capacity(kind: ComponentType, capacity: usize) -> Values {
        match kind {
            ComponentType::I8 => Values::I8(Vec::with_capacity(capacity)),
            ComponentType::U8 => Values::U8(Vec::with_capacity(capacity)),
            ComponentType::I16 => Values::I16(Vec::with_capacity(capacity)),
            ComponentType::U16 => Values::U16(Vec::with_capacity(capacity)),
            ComponentType::U32 => Values::U32(Vec::with_capacity(capacity)),
            ComponentType::F32 => Values::F32(Vec::with_capacity(capacity)),
        }
    }

    /// Appends the little-endian bytes of components `range` to `out`.
    pub fn write_le(&self, range: std::ops::Range<usize>, out: &mut Vec<u8>) {
        each_values!(self, v => v[range].iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes())))
    }

    /// Appends components decoded from little-endian `bytes` (a whole number of components).
    pub fn push_le(&mut self, bytes: &[u8]) {
        macro_rules! push {
            ($v:ident, $t:ty) => {{
                const N: usize = std::mem::size_of::<$t>();
                $v.extend(
                    bytes
                        .chunks_exact(N)
                        .map(|b| <$t>::from_le_bytes(b.try_into().expect("chunk of N bytes"))),
                )
            }};
        }
        match self {
            Values::I8(v) => push!(v, i8),
            Values::U8(v) => push!(v, u8),
            Values::I16(v) => push!(v, i16),
            Values::U16(v) => push!(v, u16),
            Values::U32(v) => push!(v, u32),
            Values::F32(v) => push!(v, f32),
        }
    }

    /// Component `i` as f64 (exact for every type), not normalized.
    pub fn get_f64(&self, i: usize) -> f64 {
        each_values!(self, v => f64::from(v[i]))
    }

    /// Index of the first non-finite component (f32 only).
    pub fn first_non_finite(&self) -> Option<usize> {
        match self {
            Values::F32(v) => v.iter().position(|x| !x.is_finite()),
            _ => None,
        }
    }
}

/// An attribute: its meaning, its values, and which value each vertex or corner has.
#[derive(Debug, Clone, PartialEq)]
pub struct Attribute {
    /// What it means.
    pub semantic: Semantic,
    /// Components per value (1 to 4; see [`Semantic::allowed_components`]).
    pub components: u8,
    /// Integers stand for [0, 1] (unsigned) or [−1, 1] (signed), as glTF's `normalized`.
    pub normalized: bool,
    /// The values, `components` numbers each.
    pub values: Values,
    /// `None`: one value per vertex, in vertex order. `Some(index)`: per corner, value
    /// `index[3t + k]` at corner `k` of triangle `t` (a "wedge" index, as OBJ's `v/vt/vn`).
    pub corners: Option<Vec<u32>>,
}

impl Attribute {
    /// A per-vertex attribute of f32 values, `N` components each.
    pub fn per_vertex<const N: usize>(semantic: Semantic, values: &[[f32; N]]) -> Attribute {
        Attribute {
            semantic,
            components: N as u8,
            normalized: false,
            values: Values::F32(values.iter().flatten().copied().collect()),
            corners: None,
        }
    }

    /// A per-corner attribute of f32 values, `N` components each, and a value index per corner.
    pub fn per_corner<const N: usize>(
        semantic: Semantic,
        values: &[[f32; N]],
        corners: Vec<u32>,
    ) -> Attribute {
        Attribute {
            corners: Some(corners),
            ..Attribute::per_vertex(semantic, values)
        }
    }

    /// Per-vertex RGBA colors of set 0, one byte a channel (normalized).
    pub fn rgba8(values: &[[u8; 4]]) -> Attribute {
        Attribute {
            semantic: Semantic::Color(0),
            components: 4,
            normalized: true,
            values: Values::U8(values.iter().flatten().copied().collect()),
            corners: None,
        }
    }

    /// Number of values.
    pub fn value_count(&self) -> usize {
        self.values.len() / usize::from(self.components.max(1))
    }

    /// Whether values are given per corner.
    pub fn is_per_corner(&self) -> bool {
        self.corners.is_some()
    }

    /// Index of the value at corner `k` of triangle `t` (`triangle` its vertices).
    pub fn value_index(&self, t: usize, k: usize, triangle: [u32; 3]) -> usize {
        match &self.corners {
            Some(index) => index[3 * t + k] as usize,
            None => triangle[k] as usize,
        }
    }

    /// Value `i` as f32 numbers (normalized integers mapped as glTF maps them).
    pub fn value_f32(&self, i: usize) -> Vec<f32> {
        let n = usize::from(self.components);
        (n * i..n * i + n)
            .map(|j| {
                let kind = self.values.component_type();
                kind.to_f32(self.values.get_f64(j), self.normalized)
            })
            .collect()
    }

    /// The little-endian bytes of value `i`: equal bytes, equal value (f32 compared bit for bit).
    pub fn value_bytes(&self, i: usize, out: &mut Vec<u8>) {
        let n = usize::from(self.components);
        self.values.write_le(n * i..n * i + n, out);
    }

    /// The per-corner bytes of every corner: for comparing two meshes corner by corner.
    pub fn corner_bytes(&self, t: usize, k: usize, triangle: [u32; 3]) -> Vec<u8> {
        let mut out = Vec::new();
        self.value_bytes(self.value_index(t, k, triangle), &mut out);
        out
    }
}
