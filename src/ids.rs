//! Typed ids for corners, vertices and triangles, so that one cannot be passed for another.

/// Marks a missing reference in stored tables: no opposite corner, no corner for a vertex.
pub const NONE: u32 = u32::MAX;

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub struct $name(pub u32);

        impl $name {
            /// The id as an index into a table.
            #[inline]
            pub fn idx(self) -> usize {
                self.0 as usize
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                self.0.fmt(f)
            }
        }
    };
}

id_type!(
    /// A corner: one vertex use in one triangle.
    Corner
);
id_type!(
    /// A vertex.
    Vertex
);
id_type!(
    /// A triangle.
    Triangle
);

impl Corner {
    /// A corner id as tables store it: [`NONE`] stands for no
    /// corner (across a boundary, or for a vertex without triangles).
    #[inline(always)]
    pub fn from_stored(raw: u32) -> Option<Corner> {
        (raw != NONE).then_some(Corner(raw))
    }
}
