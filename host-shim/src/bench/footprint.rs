//! Static memory footprint of the CLIPS builds: file sizes and `size` sections.

use std::path::{Path, PathBuf};
use std::process::Command;

/// One binary or shared library.
#[derive(Clone, Debug)]
pub struct Footprint {
    pub label: String,
    pub path: PathBuf,
    pub file_bytes: u64,
    /// `text`, `data`, `bss` from binutils `size`, when it is installed.
    pub sections: Option<Sections>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sections {
    pub text: u64,
    pub data: u64,
    pub bss: u64,
}

fn footprint(label: &str, path: &Path) -> Option<Footprint> {
    let path = path.canonicalize().ok()?;
    let file_bytes = std::fs::metadata(&path).ok()?.len();
    let sections = Command::new("size")
        .arg(&path)
        .output()
        .ok()
        .and_then(|out| parse_berkeley_size(&String::from_utf8_lossy(&out.stdout)));
    Some(Footprint {
        label: label.to_string(),
        path,
        file_bytes,
        sections,
    })
}

/// Reads the second line of `size` (Berkeley format): `text data bss dec hex file`.
pub fn parse_berkeley_size(stdout: &str) -> Option<Sections> {
    let mut numbers = stdout.lines().nth(1)?.split_whitespace();
    let mut next = || numbers.next()?.parse().ok();
    Some(Sections {
        text: next()?,
        data: next()?,
        bss: next()?,
    })
}

/// Where `program` lives on PATH.
fn which(program: &str) -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join(program))
            .find(|candidate| candidate.is_file())
    })
}

/// The `clips` binary and the `libclips` it links, as `ldd` resolves it.
pub fn clips_630() -> Vec<Footprint> {
    let Some(binary) = which("clips") else {
        return Vec::new();
    };
    let mut found: Vec<Footprint> = footprint("clips (6.30 binary)", &binary)
        .into_iter()
        .collect();
    let library = Command::new("ldd")
        .arg(&binary)
        .output()
        .ok()
        .and_then(|out| library_path(&String::from_utf8_lossy(&out.stdout), "libclips"));
    if let Some(library) = library {
        found.extend(footprint("libclips (6.30 library)", &library));
    }
    found
}

/// The resolved path of the first `ldd` line naming `library`.
pub fn library_path(ldd_stdout: &str, library: &str) -> Option<PathBuf> {
    ldd_stdout
        .lines()
        .filter(|line| line.contains(library))
        .find_map(|line| line.split_once("=>")?.1.split_whitespace().next())
        .map(PathBuf::from)
}

/// The compiled CLIPS 6.4 library inside clipspy.
pub fn clipspy(python: &str) -> Option<Footprint> {
    let out = Command::new(python)
        .args(["-c", "import clips._clips as c; print(c.__file__)"])
        .output()
        .ok()?;
    let path = String::from_utf8_lossy(&out.stdout).trim().to_string();
    if path.is_empty() {
        return None;
    }
    footprint("clipspy _clips (6.4 library)", Path::new(&path))
}

/// What the footprint tool (`cargo run -p tests --bin footprint -- --json-out F`)
/// reports about the agent image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ImageFootprint {
    pub path: String,
    pub code_bytes: u64,
    /// Statics plus measured stack.
    pub ram_bytes: u64,
    pub static_bytes: u64,
    pub stack_bytes: u64,
    /// The engine static, once the image holds it.
    pub arena_bytes: Option<u64>,
}

/// Reads the footprint tool's JSON.
pub fn image_footprint(path: &Path) -> Result<ImageFootprint, String> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        format!(
            "not measured: {} ({e}); run `cargo run -p tests --bin footprint -- --json-out {}` first",
            path.display(),
            path.display()
        )
    })?;
    parse_image_footprint(&text)
        .ok_or_else(|| format!("{}: not the footprint tool's JSON", path.display()))
}

pub fn parse_image_footprint(text: &str) -> Option<ImageFootprint> {
    let json: serde_json::Value = serde_json::from_str(text).ok()?;
    let ram = &json["ram"];
    Some(ImageFootprint {
        path: json["image"].as_str()?.to_string(),
        code_bytes: json["code"]["bytes"].as_u64()?,
        ram_bytes: ram["bytes"].as_u64()?,
        static_bytes: ram["static_bytes"].as_u64()?,
        stack_bytes: ram["stack_max_bytes"].as_u64().unwrap_or(0),
        arena_bytes: ram["engine_arena"]["bytes"].as_u64(),
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn footprint_json_is_read() {
        let json = r#"{"code": {"bytes": 36355}, "image": "/x/agent-image",
            "ram": {"bytes": 920, "static_bytes": 388, "stack_max_bytes": 532,
                    "engine_arena": {"bytes": null, "present": false}}}"#;
        let image = super::parse_image_footprint(json).expect("valid");
        assert_eq!(image.code_bytes, 36355);
        assert_eq!(image.ram_bytes, 920);
        assert_eq!(image.arena_bytes, None);
        assert!(super::parse_image_footprint("{}").is_none());
    }

    use super::*;

    #[test]
    fn size_and_ldd_outputs_are_read() {
        let size = "   text\t   data\t    bss\t    dec\t    hex\tfilename\n\
                    1016512\t  26848\t  19408\t1062768\t 103770\t/lib/libclips.so.6\n";
        assert_eq!(
            parse_berkeley_size(size),
            Some(Sections {
                text: 1_016_512,
                data: 26_848,
                bss: 19_408
            })
        );
        let ldd =
            "\tlinux-vdso.so.1 (0x00007ffd)\n\tlibclips.so.6 => /lib/libclips.so.6 (0x7f1d)\n";
        assert_eq!(
            library_path(ldd, "libclips"),
            Some(PathBuf::from("/lib/libclips.so.6"))
        );
        assert_eq!(library_path(ldd, "libfoo"), None);
    }
}
