//! The shop's tool table: which insert each T number holds, so that a program's `T0303` chooses
//! the insert threadcheck cuts with.
//!
//! ```toml
//! # T number = "full", "partial", "partial:TIP_RADIUS" or an insert TOML file (relative to this file)
//! [tools]
//! 3 = "full"
//! 4 = "partial:0.05"
//! 7 = "inserts/tr-30deg.toml"
//! ```

use crate::analysis::verify::InsertChoice;
use crate::Error;
use std::collections::BTreeMap;
use std::path::Path;

/// T numbers and their inserts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ToolTable {
    /// Where the table came from, for messages.
    pub source: String,
    tools: BTreeMap<u32, (InsertChoice, String)>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    tools: BTreeMap<String, String>,
}

impl ToolTable {
    /// Reads a tool table; insert files are taken relative to `dir`.
    ///
    /// ```
    /// use threadcheck::ToolTable;
    /// use threadcheck::InsertChoice;
    /// let t = ToolTable::from_toml("[tools]\n3 = \"full\"\n", "tools.toml", std::path::Path::new("."))?;
    /// assert_eq!(t.insert(3).map(|x| &x.0), Some(&InsertChoice::Full));
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn from_toml(text: &str, source: &str, dir: &Path) -> Result<ToolTable, Error> {
        let ferr = |m: String| Error::File { file: source.to_string(), message: m };
        let raw: Raw = toml::from_str(text).map_err(|e| ferr(e.to_string().replace('\n', " ")))?;
        let mut tools = BTreeMap::new();
        for (k, v) in raw.tools {
            let t: u32 = k
                .trim_start_matches(['T', 't'])
                .parse()
                .map_err(|_| ferr(format!("tool '{k}' is not a T number (write 3 = \"full\")")))?;
            let choice = match v.parse::<crate::analysis::verify::InsertChoice>()? {
                InsertChoice::File(p) if p.is_relative() => InsertChoice::File(dir.join(p)),
                c => c,
            };
            tools.insert(t, (choice, v));
        }
        Ok(ToolTable { source: source.to_string(), tools })
    }

    /// Reads a tool table file.
    pub fn read(path: &Path) -> Result<ToolTable, Error> {
        let shown = path.display().to_string();
        let text = crate::ground::input::read_text_bounded(
            path,
            crate::ground::bounds::MAX_DATA_FILE_BYTES,
            "a tool table",
        )?;
        ToolTable::from_toml(&text, &shown, path.parent().unwrap_or(Path::new(".")))
    }

    /// The first tool whose insert is a file, and how the table wrote it (a server reads no
    /// file).
    pub fn file_entry(&self) -> Option<(u32, &str)> {
        self.tools.iter().find_map(|(t, (c, w))| match c {
            InsertChoice::File(_) => Some((*t, w.as_str())),
            InsertChoice::Full | InsertChoice::Partial { .. } | InsertChoice::Toml { .. } => None,
        })
    }

    /// The insert of tool `t` and how the table wrote it.
    pub fn insert(&self, t: u32) -> Option<&(InsertChoice, String)> {
        self.tools.get(&t)
    }
}
