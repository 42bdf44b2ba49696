//! Regenerates `jobs/models/facade.obj`, the mesh facade of `jobs/mesh-facade.ron`:
//! a doubly curved facade 1.8 m × 1.2 m sampled on a 90 × 60 grid (20 mm spacing).
//!
//! ```text
//! cargo run -p hotcut --example facade_mesh
//! ```

use geom::expr::Expr;
use geom::heightfield::HeightField;

/// The facade's height in millimetres; the same expression is in the job's comment.
pub const FACADE_Z: &str = "90*sin(x/380)*cos(y/330) + 35*cos(x/260)";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let hf = HeightField::try_new(Expr::parse(FACADE_Z)?, (0.0, 1800.0), (0.0, 1200.0))?;
    let mesh = hf.to_mesh(90, 60)?;
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs/models/facade.obj");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&path)?);
    export::obj::write_mesh(
        &mut f,
        &mesh,
        4,
        export::SourceUnits {
            name: "Millimetre",
            metres: 1e-3,
        },
    )?;
    println!(
        "wrote {} ({} vertices, {} faces)",
        path.display(),
        mesh.vertices().len(),
        mesh.faces().len()
    );
    Ok(())
}
