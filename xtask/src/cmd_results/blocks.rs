//! The marked blocks of a docs file and the markdown tables inside them: find, replace, and
//! compare cell by cell (what `--check` reports).

use std::fmt::Write as _;

/// `<!-- results:NAME -->`.
pub fn begin_marker(name: &str) -> String {
    format!("<!-- results:{name} -->")
}

/// `<!-- /results:NAME -->`.
pub fn end_marker(name: &str) -> String {
    format!("<!-- /results:{name} -->")
}

/// Byte range of the content between the block's markers in `page`.
pub fn find(page: &str, name: &str) -> Result<std::ops::Range<usize>, String> {
    let (b, e) = (begin_marker(name), end_marker(name));
    let Some(start) = page.find(&b) else {
        return Err(format!(
            "no `{b}` ... `{e}` block (add the two markers where the table goes)"
        ));
    };
    let from = start + b.len();
    let Some(len) = page[from..].find(&e) else {
        return Err(format!("`{b}` without its closing `{e}`"));
    };
    if page[from + len + e.len()..].contains(&b) {
        return Err(format!("`{b}` appears twice"));
    }
    Ok(from..from + len)
}

/// `page` with the block's content replaced by `content` (framed by blank lines).
pub fn replace(page: &str, name: &str, content: &str) -> Result<String, String> {
    let r = find(page, name)?;
    Ok(format!(
        "{}\n\n{}\n\n{}",
        &page[..r.start],
        content.trim(),
        &page[r.end..]
    ))
}

/// A markdown table: header cells and rows of cells.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// Column names.
    pub header: Vec<String>,
    /// Rows, each as many cells as the header.
    pub rows: Vec<Vec<String>>,
    /// How many leading cells name a row (the rest are its figures).
    pub key_columns: usize,
}

fn cells(line: &str) -> Vec<String> {
    let t = line.trim().trim_start_matches('|').trim_end_matches('|');
    t.split('|').map(|c| c.trim().to_string()).collect()
}

impl Table {
    /// A table with these columns, the first `key_columns` naming a row.
    pub fn new(header: &[&str], key_columns: usize) -> Table {
        Table {
            header: header.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
            key_columns,
        }
    }

    /// Append a row (as many cells as columns).
    pub fn push(&mut self, row: Vec<String>) {
        debug_assert_eq!(row.len(), self.header.len());
        self.rows.push(row);
    }

    /// The first markdown table in `text` (lines starting with `|`).
    pub fn parse(text: &str, key_columns: usize) -> Table {
        let lines: Vec<&str> = text
            .lines()
            .skip_while(|l| !l.trim_start().starts_with('|'))
            .take_while(|l| l.trim_start().starts_with('|'))
            .collect();
        let mut t = Table {
            key_columns,
            ..Table::default()
        };
        if let Some(h) = lines.first() {
            t.header = cells(h);
        }
        t.rows = lines.iter().skip(2).map(|l| cells(l)).collect();
        t
    }

    /// The table as markdown.
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "| {} |", self.header.join(" | "));
        let _ = writeln!(s, "|{}", "---|".repeat(self.header.len()));
        for r in &self.rows {
            let _ = writeln!(s, "| {} |", r.join(" | "));
        }
        s
    }

    /// A row's name: its key cells joined.
    pub fn key(&self, row: &[String]) -> String {
        row.iter()
            .take(self.key_columns)
            .cloned()
            .collect::<Vec<_>>()
            .join(" / ")
    }

    /// The row named `key`.
    pub fn row(&self, key: &str) -> Option<&Vec<String>> {
        self.rows.iter().find(|r| self.key(r) == key)
    }
}

/// What differs between the table in the docs (`old`) and the one HEAD gives (`new`), one line
/// per row: the row's name and each differing column as `old -> new`.
pub fn differences(old: &Table, new: &Table) -> Vec<String> {
    let mut out = Vec::new();
    if old.header != new.header {
        out.push(format!(
            "columns: `{}` -> `{}`",
            old.header.join(" | "),
            new.header.join(" | ")
        ));
        return out;
    }
    for r in &new.rows {
        let key = new.key(r);
        match old.row(&key) {
            None => out.push(format!("row `{key}`: missing from the docs")),
            Some(o) => {
                let changed: Vec<String> = new
                    .header
                    .iter()
                    .enumerate()
                    .skip(new.key_columns)
                    .filter(|(i, _)| o.get(*i) != r.get(*i))
                    .map(|(i, h)| {
                        format!(
                            "{h} {} -> {}",
                            o.get(i).map_or("<none>", String::as_str),
                            r[i]
                        )
                    })
                    .collect();
                if !changed.is_empty() {
                    out.push(format!("row `{key}`: {}", changed.join(", ")));
                }
            }
        }
    }
    for o in &old.rows {
        let key = old.key(o);
        if new.row(&key).is_none() {
            out.push(format!("row `{key}`: in the docs but not produced at HEAD"));
        }
    }
    if out.is_empty() && old.rows.len() != new.rows.len() {
        out.push("rows repeated or in another order".into());
    }
    if out.is_empty() && old.rows != new.rows {
        out.push("rows in another order".into());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_are_found_replaced_and_refused_when_malformed() {
        let page = "# T\n\n<!-- results:a -->\nold\n<!-- /results:a -->\ntail\n";
        let new = replace(page, "a", "| x |\n|---|\n| 1 |\n").unwrap();
        assert_eq!(
            new,
            "# T\n\n<!-- results:a -->\n\n| x |\n|---|\n| 1 |\n\n<!-- /results:a -->\ntail\n"
        );
        // Replacing again gives the same page.
        assert_eq!(replace(&new, "a", "| x |\n|---|\n| 1 |").unwrap(), new);
        assert!(find(page, "b").unwrap_err().contains("<!-- results:b -->"));
        assert!(find("<!-- results:a -->", "a")
            .unwrap_err()
            .contains("closing"));
        let twice = format!("{page}{page}");
        assert!(find(&twice, "a").unwrap_err().contains("twice"));
    }

    #[test]
    fn differences_name_the_row_and_the_numbers() {
        let mut new = Table::new(&["method", "setting", "SR", "SPL"], 2);
        new.push(vec![
            "random".into(),
            "Tel-Hop".into(),
            "6.0".into(),
            "4.5".into(),
        ]);
        new.push(vec![
            "semantic".into(),
            "Tel-Hop".into(),
            "10.0".into(),
            "8.3".into(),
        ]);
        let parsed = Table::parse(&format!("text\n\n{}\nmore", new.markdown()), 2);
        assert_eq!(parsed, new);
        assert!(differences(&parsed, &new).is_empty());
        let mut old = new.clone();
        old.rows[1][2] = "8.0".into();
        old.rows
            .push(vec!["gone".into(), "-".into(), "1".into(), "1".into()]);
        let d = differences(&old, &new);
        assert_eq!(
            d,
            vec![
                "row `semantic / Tel-Hop`: SR 8.0 -> 10.0".to_string(),
                "row `gone / -`: in the docs but not produced at HEAD".to_string(),
            ]
        );
        let mut swapped = new.clone();
        swapped.rows.swap(0, 1);
        assert_eq!(differences(&swapped, &new), vec!["rows in another order"]);
    }
}
