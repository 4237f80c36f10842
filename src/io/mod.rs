//! Mesh importers and exporters: OBJ, OFF, PLY, STL.
