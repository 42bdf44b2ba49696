use geom::mesh::TriMesh;

/// A placed block (centre, rotation, size) as a closed box mesh.
///
/// # Errors
/// When the box is degenerate (a zero edge).
pub fn block_mesh(p: &blocks::Placement) -> export::Result<TriMesh> {
    TriMesh::try_new(
        p.cuboid().corners().to_vec(),
        geom::mesh::BOX_FACES.to_vec(),
    )
    .map_err(|e| export::ExportError::Io(std::io::Error::other(e.to_string())))
}
