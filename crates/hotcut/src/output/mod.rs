//! Writers shared by the tasks: the [`Files`](crate::output::Files) a run renders, and the robot
//! files (`targets.json`/`targets.csv`, ABB RAPID) of every task that poses the blade.
//! Format-generic helpers (glTF meshes from `geom` meshes and boxes, SVG bounds) live in
//! the `export` crate.

/// The deviation chart of the drawings.
pub mod chart;
/// The number formats of the tasks' `report.html` pages.
pub mod page;
/// Robot targets and RAPID programs from blade poses.
pub mod robot;

use std::path::{Path, PathBuf};

/// A deviation's glTF vertex colour: blue at 0, green at half the tolerance, red at or
/// beyond it.
pub fn deviation_color(dev: f64, tolerance: f64) -> [f32; 4] {
    let t = if tolerance > 0.0 {
        (dev / tolerance).clamp(0.0, 1.0)
    } else {
        1.0
    };
    let r = (2.0 * t - 1.0).clamp(0.0, 1.0);
    let g = 1.0 - (2.0 * t - 1.0).abs();
    let b = (1.0 - 2.0 * t).clamp(0.0, 1.0);
    [r as f32, g as f32, b as f32, 1.0]
}

/// The unit the job's lengths are in, for the 3D writers (glTF scales to metres, OBJ
/// names it).
pub fn source_units(units: crate::spec::Units) -> export::SourceUnits<'static> {
    export::SourceUnits {
        name: units.name(),
        metres: 1e-3 / units.per_mm(),
    }
}

/// An OBJ writer for output `o` (its `axes`) of a job in `units`, `decimals` digits.
pub fn obj_writer(
    decimals: usize,
    units: crate::spec::Units,
    o: &crate::spec::OutputSpec,
) -> export::obj::ObjWriter {
    let up = match o {
        crate::spec::OutputSpec::Obj {
            axes: crate::spec::ObjAxes::YUp,
        } => export::obj::UpAxis::Y,
        _ => export::obj::UpAxis::Z,
    };
    export::obj::ObjWriter::with_up(decimals, source_units(units), up)
}

/// The translucent grey blocks of the hot-blade tasks' `model.gltf`.
pub fn block_material() -> export::gltf::Material {
    export::gltf::Material::new("block", [0.85, 0.85, 0.8, 0.15], true)
}

/// The files of one run, written one by one into the run's (temporary) output folder in
/// the order the job lists its outputs: each is rendered into memory, written, and
/// dropped, so a run holds one file at a time.
/// A run can also render files into memory ([`Files::in_memory`]), as `report.html` does
/// with the drawings it inlines.
#[derive(Debug)]
pub struct Files {
    /// The folder written into; `None` keeps the files in `kept`.
    dir: Option<PathBuf>,
    names: Vec<String>,
    kept: Vec<(String, Vec<u8>)>,
}

impl Files {
    /// Files written into `dir`.
    pub fn new(dir: &Path) -> Self {
        Self {
            dir: Some(dir.to_path_buf()),
            names: Vec::new(),
            kept: Vec::new(),
        }
    }

    /// Files kept in memory (see [`Files::into_kept`]).
    pub fn in_memory() -> Self {
        Self {
            dir: None,
            names: Vec::new(),
            kept: Vec::new(),
        }
    }

    /// The files kept in memory, (name, bytes) in order (empty for files written to a
    /// folder).
    pub fn into_kept(self) -> Vec<(String, Vec<u8>)> {
        self.kept
    }

    /// The folder files are written into (`None` in memory).
    pub fn dir(&self) -> Option<&Path> {
        self.dir.as_deref()
    }

    /// Renders file `name` with `write` and writes it. On error the file is the last
    /// named, so the caller can say which one failed.
    ///
    /// # Errors
    /// `write`'s, or the file system's.
    pub fn add(
        &mut self,
        name: impl Into<String>,
        write: impl FnOnce(&mut Vec<u8>) -> export::Result<()>,
    ) -> export::Result<()> {
        let name = name.into();
        if self.names.contains(&name) {
            return Err(export::ExportError::Data(format!(
                "two outputs would both be written as {name}"
            )));
        }
        self.names.push(name.clone());
        let mut buf = Vec::new();
        write(&mut buf)?;
        match &self.dir {
            Some(dir) => {
                let path = dir.join(&name);
                if let Some(parent) = path.parent() {
                    std::fs::create_dir_all(parent)?;
                }
                std::fs::write(path, buf)?
            }
            None => self.kept.push((name, buf)),
        }
        Ok(())
    }

    /// The bytes of file `name` written so far (read back from the folder, or kept).
    pub fn bytes(&self, name: &str) -> Option<Vec<u8>> {
        match &self.dir {
            Some(dir) => std::fs::read(dir.join(name)).ok(),
            None => self
                .kept
                .iter()
                .find(|(n, _)| n == name)
                .map(|(_, b)| b.clone()),
        }
    }

    /// The size of file `name` in bytes (0 when it is not there).
    pub fn size(&self, name: &str) -> u64 {
        match &self.dir {
            Some(dir) => std::fs::metadata(dir.join(name)).map_or(0, |m| m.len()),
            None => self
                .kept
                .iter()
                .find(|(n, _)| n == name)
                .map_or(0, |(_, b)| b.len() as u64),
        }
    }

    /// Writes file `name` holding `text`.
    ///
    /// # Errors
    /// The file system's.
    pub fn text(&mut self, name: impl Into<String>, text: String) -> export::Result<()> {
        self.add(name, |buf| {
            buf.extend(text.into_bytes());
            Ok(())
        })
    }

    /// Writes file `name` holding `value` as JSON rounded to `digits` significant digits.
    ///
    /// # Errors
    /// When `value` cannot be serialised, or the file system's.
    pub fn json(
        &mut self,
        name: impl Into<String>,
        value: &impl serde::Serialize,
        digits: usize,
    ) -> export::Result<()> {
        self.add(name, |buf| {
            buf.extend(export::json::to_json_string(value, digits)?.into_bytes());
            Ok(())
        })
    }

    /// How many files were named so far.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether no file was named yet.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// Name of the last file (the one that failed, after an error).
    pub fn last_name(&self) -> Option<&str> {
        self.names.last().map(String::as_str)
    }

    /// The names named so far, in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The names written, in order.
    pub fn into_names(self) -> Vec<String> {
        self.names
    }
}
