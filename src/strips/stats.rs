//! The strip figures of `lrmesh stats` (JSON object `strips`).

use super::{lr_index_list, stripify, Cts, StripOptions};
use crate::corner_table::CornerTable;
use crate::error::Result;
use crate::lr::{Lr, LrOptions};
use crate::mesh::Mesh;

/// Triangle strips, constrained strips and the LR index list of one mesh.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StripStats {
    /// Indices per input triangle of [`stripify`] with default options: strips (restarts and
    /// swaps included), fans and lone triangles.
    pub indices_per_triangle: f64,
    /// Number of strips.
    pub strips: u32,
    /// Number of fans.
    pub fans: u32,
    /// Triangles drawn alone (isolated, degenerate or out of range).
    pub isolated_triangles: u32,
    /// Constrained triangle strips `T` plus the adjacent-strips table `A`, 32 bits an entry,
    /// per triangle of the corner table.
    pub cts_bits_per_triangle: f64,
    /// References per triangle of the LR rendering index list (default LR options).
    pub lr_index_rpt: f64,
}

impl StripStats {
    /// The figures of `mesh`.
    ///
    /// # Errors
    /// As [`CornerTable::build`], [`Cts::build`] and [`Lr::build`]: a mesh beyond their id
    /// spaces.
    pub fn of(mesh: &Mesh) -> Result<StripStats> {
        StripStats::with_options(mesh, &StripOptions::default(), &LrOptions::default())
    }

    /// The figures of `mesh` with the given stripping and LR options.
    ///
    /// # Errors
    /// As [`StripStats::of`].
    pub fn with_options(
        mesh: &Mesh,
        options: &StripOptions,
        lr_options: &LrOptions,
    ) -> Result<StripStats> {
        let table = CornerTable::from_mesh(mesh)?;
        let lr = Lr::build(&table, lr_options)?;
        StripStats::from_built(mesh, &table, &lr, options)
    }

    /// The figures of `mesh` from its corner table and LR already built (`lrmesh stats`
    /// builds each once for every report).
    ///
    /// # Errors
    /// As [`StripStats::of`].
    pub fn from_built(
        mesh: &Mesh,
        table: &CornerTable,
        lr: &Lr,
        options: &StripOptions,
    ) -> Result<StripStats> {
        let strips = stripify(mesh.positions.len(), &mesh.triangles, options);
        let cts = Cts::build(table, options)?;
        Ok(StripStats {
            indices_per_triangle: strips.indices_per_triangle(),
            strips: strips.strip_count,
            fans: strips.fan_count,
            isolated_triangles: (strips.list.len() / 3) as u32,
            cts_bits_per_triangle: cts.bits_per_triangle(),
            lr_index_rpt: lr_index_list(lr).references_per_triangle(),
        })
    }
}

impl std::fmt::Display for StripStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "triangle strips")?;
        writeln!(
            f,
            "  indices per triangle     {:.3}",
            self.indices_per_triangle
        )?;
        writeln!(f, "  strips                   {}", self.strips)?;
        writeln!(f, "  fans                     {}", self.fans)?;
        writeln!(f, "  isolated triangles       {}", self.isolated_triangles)?;
        writeln!(
            f,
            "  CTS bits per triangle    {:.1}",
            self.cts_bits_per_triangle
        )?;
        writeln!(f, "  LR index list rpt        {:.3}", self.lr_index_rpt)
    }
}
