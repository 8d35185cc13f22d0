//! Reading tables from text files: MSL's text format (`#1`, then `double name(rows,
//! cols)` headers followed by the numbers) and plain CSV (numbers separated by commas,
//! semicolons or blanks, an optional first line of column names, `#` comments).

use std::path::Path;

/// Reads the table `name` of the file at `path`: in MSL's text format when the file
/// starts with `#1` (the matrix `name`), else CSV (the whole file; `name` unused).
/// Rows of numbers; the error says what is wrong and where.
pub fn read_table(path: &Path, name: &str) -> Result<Vec<Vec<f64>>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read the table file {}: {e}", path.display()))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let at = |e: String| format!("{}: {e}", path.display());
    if text.starts_with("#1") {
        msl_text_table(text, name).map_err(at)
    } else {
        csv_table(text).map_err(at)
    }
}

/// The numbers of a data line (up to a `#` comment), split at blanks, commas and
/// semicolons; `Err` with the first token that is not a number.
fn numbers(line: &str) -> Result<Vec<f64>, String> {
    let line = line.split('#').next().unwrap_or("");
    line.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|t| !t.is_empty())
        .map(|t| t.parse::<f64>().map_err(|_| t.to_string()))
        .collect()
}

/// The matrix `name` of MSL's text format.
fn msl_text_table(text: &str, name: &str) -> Result<Vec<Vec<f64>>, String> {
    let mut lines = text.lines().enumerate().skip(1);
    let (rows, cols) = loop {
        let Some((_, line)) = lines.next() else {
            return Err(format!("table matrix \"{name}\" not found"));
        };
        let tokens: Vec<&str> = line
            .split(|c: char| c.is_whitespace() || "(,)".contains(c))
            .filter(|t| !t.is_empty())
            .collect();
        if tokens.len() >= 4
            && (tokens[0] == "double" || tokens[0] == "float")
            && tokens[1] == name
            && let (Ok(r), Ok(c)) = (tokens[2].parse::<usize>(), tokens[3].parse::<usize>())
        {
            break (r, c);
        }
    };
    let mut values = Vec::with_capacity(rows * cols);
    while values.len() < rows * cols {
        let Some((k, line)) = lines.next() else {
            return Err(format!(
                "end of file after {} of the {} numbers of \"{name}\"",
                values.len(),
                rows * cols
            ));
        };
        let trimmed = line.trim_start();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let row = numbers(trimmed).map_err(|t| format!("line {}: `{t}` is not a number", k + 1))?;
        if values.len() + row.len() > rows * cols {
            return Err(format!(
                "line {}: more numbers than the {rows} x {cols} of \"{name}\"",
                k + 1
            ));
        }
        values.extend(row);
    }
    Ok(values.chunks(cols.max(1)).map(<[f64]>::to_vec).collect())
}

/// A CSV table: every line of numbers a row, all of one length; a first line that is
/// not numbers (column names) is skipped.
fn csv_table(text: &str) -> Result<Vec<Vec<f64>>, String> {
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        match numbers(trimmed) {
            Ok(row) if row.is_empty() => {}
            Ok(row) => {
                if let Some(first) = rows.first()
                    && first.len() != row.len()
                {
                    return Err(format!(
                        "line {}: {} numbers, the rows before have {}",
                        k + 1,
                        row.len(),
                        first.len()
                    ));
                }
                rows.push(row);
            }
            Err(_) if rows.is_empty() => {} // the column names
            Err(t) => return Err(format!("line {}: `{t}` is not a number", k + 1)),
        }
    }
    if rows.is_empty() {
        return Err("no rows of numbers".into());
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn msl_text_format_finds_its_matrix_among_others() {
        let text =
            "#1\ndouble tab0(1,2)\n 9 9\ndouble tab1(3,2) # comment\n 0 0\n 1 1 # one\n\n 2 4\n";
        let t = msl_text_table(text, "tab1").unwrap();
        assert_eq!(t, vec![vec![0.0, 0.0], vec![1.0, 1.0], vec![2.0, 4.0]]);
        // Rows may share a line or span several.
        let t = msl_text_table("#1\nfloat a 2 2\n1 2 3\n4\n", "a").unwrap();
        assert_eq!(t, vec![vec![1.0, 2.0], vec![3.0, 4.0]]);
        assert!(
            msl_text_table(text, "tab2")
                .unwrap_err()
                .contains("not found")
        );
        let short = msl_text_table("#1\ndouble a(2,2)\n1 2 3\n", "a").unwrap_err();
        assert!(short.contains("end of file after 3 of the 4"), "{short}");
        let bad = msl_text_table("#1\ndouble a(1,2)\n1 x\n", "a").unwrap_err();
        assert!(bad.contains("line 3") && bad.contains("`x`"), "{bad}");
    }

    #[test]
    fn csv_skips_its_header_and_checks_its_rows() {
        let t = csv_table("time,value\n0,1\n# note\n1.5;2\n2 3e-1\n").unwrap();
        assert_eq!(t, vec![vec![0.0, 1.0], vec![1.5, 2.0], vec![2.0, 0.3]]);
        let ragged = csv_table("0,1\n1,2,3\n").unwrap_err();
        assert!(
            ragged.contains("line 2") && ragged.contains("3 numbers"),
            "{ragged}"
        );
        let bad = csv_table("0,1\n1,oops\n").unwrap_err();
        assert!(bad.contains("line 2") && bad.contains("`oops`"), "{bad}");
    }
}
