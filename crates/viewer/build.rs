//! Builds in every preset of the repository's `presets/` folder by its file name, so
//! a new preset is a TOML file there and nothing else (`src/presets.rs` includes
//! the table this writes).

use std::fmt::Write as _;
use std::path::Path;

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets");
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut presets: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("the presets folder {}: {e}", dir.display()))
        .filter_map(Result::ok)
        .map(|entry| entry.path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .filter_map(|path| {
            let name = path.file_stem()?.to_str()?.to_owned();
            let path = path.canonicalize().ok()?.to_str()?.to_owned();
            Some((name, path))
        })
        .collect();
    presets.sort();
    let mut table = format!(
        "/// The shipped presets, by name (the file names of `presets/`, in order).\n\
         pub const BUILT_IN: [(&str, &str); {}] = [\n",
        presets.len()
    );
    for (name, path) in &presets {
        writeln!(table, "    ({name:?}, include_str!({path:?})),").expect("a String");
    }
    table.push_str("];\n");
    let out = Path::new(&std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"))
        .join("built_in_presets.rs");
    std::fs::write(&out, table).unwrap_or_else(|e| panic!("{}: {e}", out.display()));
}
