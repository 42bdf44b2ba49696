//! Writers shared by the tasks: the [`Files`](crate::output::Files) a run renders, and the robot
//! files (`targets.json`/`targets.csv`, ABB RAPID) of every task that poses the blade.
//! Format-generic helpers (glTF meshes from `geom` meshes and boxes, SVG bounds) live in
//! the `export` crate.

/// Robot targets and RAPID programs from blade poses.
pub mod robot;

/// The files of one run, rendered into memory in the order the job lists its outputs; the
/// runner writes them into the output folder.
#[derive(Debug, Default)]
pub struct Files {
    files: Vec<(String, Vec<u8>)>,
}

impl Files {
    /// Renders file `name` with `write`. On error the file stays last in the list, so the
    /// caller can name it.
    ///
    /// # Errors
    /// `write`'s.
    pub fn add(
        &mut self,
        name: impl Into<String>,
        write: impl FnOnce(&mut Vec<u8>) -> export::Result<()>,
    ) -> export::Result<()> {
        self.files.push((name.into(), Vec::new()));
        let last = self.files.len() - 1;
        write(&mut self.files[last].1)
    }

    /// Adds file `name` holding `text`.
    pub fn text(&mut self, name: impl Into<String>, text: String) {
        self.files.push((name.into(), text.into_bytes()));
    }

    /// Adds file `name` holding `value` as JSON rounded to `digits` significant digits.
    ///
    /// # Errors
    /// When `value` cannot be serialised.
    pub fn json(
        &mut self,
        name: impl Into<String>,
        value: &impl serde::Serialize,
        digits: usize,
    ) -> export::Result<()> {
        let text = export::json::to_json_string(value, digits)?;
        self.text(name, text);
        Ok(())
    }

    /// Name of the last file added (the one that failed, after an error).
    pub fn last_name(&self) -> Option<&str> {
        self.files.last().map(|(n, _)| n.as_str())
    }

    /// The files, in order.
    pub fn into_vec(self) -> Vec<(String, Vec<u8>)> {
        self.files
    }
}
