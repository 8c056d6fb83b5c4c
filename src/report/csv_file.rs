//! CSV tables written atomically with `csv::Writer::serialize` from row structs: the header is
//! the row type's field names, the cells its fields. [`Fixed`] and [`Shortest`] pin how a
//! number is printed, so a table's bytes do not depend on the csv crate's float formatting.

use super::{ReportError, write_file};
use serde::{Serialize, Serializer};
use std::fmt;
use std::path::Path;

/// A number printed with `D` digits after the point (`format!("{:.D}")`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fixed<const D: usize>(pub f64);

impl<const D: usize> Serialize for Fixed<D> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&format_args!("{:.*}", D, self.0))
    }
}

/// A number printed in its shortest exact form (`format!("{v}")`); an empty cell when it is
/// not finite (a statistic over no data).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Shortest(pub f64);

impl Serialize for Shortest {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl fmt::Display for Shortest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_finite() {
            write!(f, "{}", self.0)
        } else {
            Ok(())
        }
    }
}

/// Writes `rows` as a CSV table to `path` atomically: one header line from the field names of
/// `R` (also for an empty table, from `R::default()`), then one line per row. On any error the
/// file at `path` is left as it was.
pub fn write_rows<R: Serialize + Default>(path: &Path, rows: &[R]) -> Result<(), ReportError> {
    let bytes = to_bytes(rows).map_err(|e| ReportError::invalid(format!("csv: {e}")))?;
    write_file(path, &bytes)
}

fn to_bytes<R: Serialize + Default>(rows: &[R]) -> Result<Vec<u8>, csv::Error> {
    let into_inner = |w: csv::Writer<Vec<u8>>| {
        w.into_inner()
            .map_err(|e| csv::Error::from(std::io::Error::other(e.to_string())))
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    if rows.is_empty() {
        // The header alone: serialize a default row and keep its first line.
        w.serialize(R::default())?;
        let bytes = into_inner(w)?;
        let end = bytes.iter().position(|b| *b == b'\n').map_or(0, |i| i + 1);
        return Ok(bytes[..end].to_vec());
    }
    for row in rows {
        w.serialize(row)?;
    }
    into_inner(w)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize, Default)]
    struct Row {
        a: usize,
        b: &'static str,
        x: Fixed<3>,
        y: Option<Fixed<2>>,
        z: Shortest,
    }

    #[derive(Serialize, Default)]
    struct Label {
        push: usize,
    }

    #[derive(Serialize, Default)]
    struct Nested {
        nested: Vec<u8>,
    }

    #[test]
    fn header_from_fields_cells_as_pinned() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.csv");
        let rows = [
            Row {
                a: 1,
                b: "x,y",
                x: Fixed(0.12345),
                y: None,
                z: Shortest(0.1),
            },
            Row {
                a: 2,
                b: "",
                x: Fixed(-2.0),
                y: Some(Fixed(1.005)),
                z: Shortest(f64::NAN),
            },
        ];
        write_rows(&path, &rows).unwrap();
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            "a,b,x,y,z\n1,\"x,y\",0.123,,0.1\n2,,-2.000,1.00,\n"
        );
        // A tuple of row structs: the headers join.
        write_rows(&path, &[(Label { push: 3 }, Row::default())]).unwrap();
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            "push,a,b,x,y,z\n3,0,,0.000,,0\n"
        );
    }

    #[test]
    fn an_empty_table_has_its_header() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.csv");
        write_rows::<Row>(&path, &[]).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "a,b,x,y,z\n");
    }

    #[test]
    fn a_row_csv_cannot_hold_keeps_the_old_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.csv");
        write_rows::<Row>(&path, &[]).unwrap();
        // A header cannot be derived from a sequence inside a struct.
        let err = write_rows(&path, &[Nested { nested: vec![1] }]).unwrap_err();
        assert!(err.to_string().contains("csv"), "{err}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "a,b,x,y,z\n");
    }
}
