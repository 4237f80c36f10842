//! stl (stub).
use super::{Loaded, ReadOptions};
use crate::error::Result;
use crate::mesh::Mesh;
use std::io::Write;
/// Reads.
pub fn read(_bytes: &[u8], _opts: &ReadOptions) -> Result<Loaded> {
    Err(super::perr(
        "stl",
        crate::Location::Whole,
        "reader not implemented yet",
    ))
}
/// Writes.
pub fn write_binary<W: Write>(_w: W, _mesh: &Mesh) -> std::io::Result<()> {
    Err(std::io::Error::other("writer not implemented yet"))
}
/// Writes.
pub fn write_ascii<W: Write>(_w: W, _mesh: &Mesh) -> std::io::Result<()> {
    Err(std::io::Error::other("writer not implemented yet"))
}
