//! What a primitive attribute's name means, which accessor types it may have, and the
//! conversion of values to f32.

use super::accessor::Decoded;
use super::document::ElementType;
use crate::mesh::{Attribute, ComponentType, Semantic, Values};

/// The meaning of a primitive attribute's name.
pub(super) enum Kind {
    Position,
    Attribute(Semantic),
    Skip(&'static str),
}

pub(super) fn kind_of(name: &str) -> Kind {
    let set = |prefix: &str| -> Option<Option<u8>> {
        let digits = name.strip_prefix(prefix)?;
        let canonical = digits == "0" || !digits.starts_with('0');
        (canonical && !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
            .then(|| digits.parse::<u8>().ok())
    };
    if name == "POSITION" {
        Kind::Position
    } else if name == "NORMAL" {
        Kind::Attribute(Semantic::Normal)
    } else if let Some(n) = set("TEXCOORD_") {
        n.map_or(Kind::Skip("a set number above 255"), |n| {
            Kind::Attribute(Semantic::TexCoord(n))
        })
    } else if let Some(n) = set("COLOR_") {
        n.map_or(Kind::Skip("a set number above 255"), |n| {
            Kind::Attribute(Semantic::Color(n))
        })
    } else if name == "TANGENT" || set("JOINTS_").is_some() || set("WEIGHTS_").is_some() {
        Kind::Skip("tangents, joints and weights are not kept")
    } else if let Some(custom) = name.strip_prefix('_').filter(|s| !s.is_empty()) {
        Kind::Attribute(Semantic::Custom(custom.to_string()))
    } else {
        Kind::Skip("not a glTF semantic, and not `_`-prefixed")
    }
}

/// Whether an accessor of this shape may hold `kind`, and what is allowed, for the message.
pub(super) fn allowed(
    kind: &Kind,
    element: ElementType,
    t: ComponentType,
    normalized: bool,
    quantized: bool,
) -> Result<(), &'static str> {
    use ComponentType::*;
    let vec = |n: u8| element == ElementType::Vector(n);
    let core_unit = t == F32 || (matches!(t, U8 | U16) && normalized);
    let ok = match kind {
        Kind::Position => vec(3) && (t == F32 || (quantized && matches!(t, I8 | U8 | I16 | U16))),
        Kind::Attribute(Semantic::Normal) => {
            vec(3) && (t == F32 || (quantized && matches!(t, I8 | I16) && normalized))
        }
        Kind::Attribute(Semantic::TexCoord(_)) => {
            vec(2) && (core_unit || (quantized && matches!(t, I8 | U8 | I16 | U16)))
        }
        Kind::Attribute(Semantic::Color(_)) => (vec(3) || vec(4)) && core_unit,
        Kind::Attribute(Semantic::Custom(_)) | Kind::Skip(_) => true,
    };
    if ok {
        return Ok(());
    }
    Err(match kind {
        Kind::Position => "VEC3 of FLOAT",
        Kind::Attribute(Semantic::Normal) => "VEC3 of FLOAT",
        Kind::Attribute(Semantic::TexCoord(_)) => {
            "VEC2 of FLOAT, or of normalized UNSIGNED_BYTE or UNSIGNED_SHORT"
        }
        _ => "VEC3 or VEC4 of FLOAT, or of normalized UNSIGNED_BYTE or UNSIGNED_SHORT",
    })
}

/// Values as f32, normalized integers mapped to fractions as glTF maps them.
pub(super) fn to_f32(d: &Decoded) -> Vec<f32> {
    if let Values::F32(v) = &d.values {
        return v.clone();
    }
    let a = Attribute {
        semantic: Semantic::Normal,
        components: d.components,
        normalized: d.normalized,
        values: d.values.clone(),
        corners: None,
    };
    (0..a.value_count()).flat_map(|i| a.value_f32(i)).collect()
}
