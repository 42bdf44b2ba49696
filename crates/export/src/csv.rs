//! CSV tables: a header line, then one line per row, fields joined by commas, numbers
//! with a fixed number of decimals ([`crate::fmt_float`]). Fields are written as given:
//! they must not hold commas, quotes or newlines (the tables hold numbers and names).

use crate::fmt_float;

/// Decimals of the numbers in every CSV file hotcut writes.
pub const CSV_DECIMALS: usize = 9;

/// A CSV table being built.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Table {
    text: String,
}

impl Table {
    /// A table with the header `columns` (comma-separated names).
    pub fn new(columns: &str) -> Self {
        Self {
            text: format!("{columns}\n"),
        }
    }

    /// Appends one row.
    pub fn row(&mut self, fields: &[String]) {
        self.text.push_str(&fields.join(","));
        self.text.push('\n');
    }

    /// `v` with [`CSV_DECIMALS`] decimals.
    pub fn num(v: f64) -> String {
        fmt_float(v, CSV_DECIMALS)
    }

    /// The table's text.
    pub fn finish(self) -> String {
        self.text
    }
}

#[cfg(test)]
mod tests {
    use super::Table;

    #[test]
    fn header_then_rows() {
        let mut t = Table::new("a,b");
        t.row(&["1".into(), Table::num(0.5)]);
        t.row(&["x".into(), Table::num(-1e-12)]);
        assert_eq!(t.finish(), "a,b\n1,0.5\nx,0\n");
    }
}
