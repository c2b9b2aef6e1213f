//! Finding a batch's inputs: files named directly, folders scanned (recursively if asked) for
//! files with an image extension that match the glob, sorted, deduplicated, checked for two
//! inputs with one output, and cut to the requested shard.

use std::collections::{HashMap, HashSet};
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use globset::{GlobBuilder, GlobMatcher};
use walkdir::WalkDir;

use super::shard::shard_key;
use super::{BatchError, BatchOptions};
use crate::export::OutputFormat;
use crate::files::read::not_a_file_kind;
use crate::files::{describe_io, printable};

/// File extensions (lower case, without the dot) of the formats the `image` crate reads with the
/// decoders this crate enables. Files found in folders are taken only with one of these.
pub const IMAGE_EXTENSIONS: &[&str] = &[
    "png", "jpg", "jpeg", "gif", "bmp", "tif", "tiff", "webp", "pbm", "pgm", "ppm", "pnm", "pam",
    "tga", "ico", "qoi", "hdr", "dds", "exr", "ff",
];

/// Whether `path` ends in one of the [`IMAGE_EXTENSIONS`], in any letter case.
pub fn is_image_path(path: &Path) -> bool {
    path.extension()
        .and_then(|extension| extension.to_str())
        .is_some_and(|extension| {
            IMAGE_EXTENSIONS
                .iter()
                .any(|known| known.eq_ignore_ascii_case(extension))
        })
}

/// One input of a batch.
#[derive(Clone, Debug)]
pub struct Input {
    /// The file as it can be opened: the folder given joined with `relative`, or the file given.
    pub source: PathBuf,
    /// Its path relative to the folder given, or its file name if it was given itself. The output
    /// mirrors it, and shards are decided by it.
    pub relative: PathBuf,
    /// Set when the folder scan could not read this entry (a broken symbolic link, a subfolder
    /// without permission); it is then reported as failed without being processed.
    pub unreadable: Option<Unreadable>,
    /// `source` with every symbolic link resolved, when that succeeded.
    canonical: Option<PathBuf>,
}

impl Input {
    /// Where the output goes, relative to the output folder: `relative` with the extension of
    /// `format`.
    pub fn output_relative(&self, format: OutputFormat) -> PathBuf {
        self.relative.with_extension(format.extension())
    }
}

/// Why the folder scan could not read an entry (shared, so that the outcome and the input can
/// both hold it).
#[derive(Clone, Debug, thiserror::Error)]
pub enum Unreadable {
    /// A symbolic link to nothing.
    #[error("broken symbolic link")]
    BrokenLink,
    /// A subfolder that cannot be listed.
    #[error("cannot read this folder: {}", describe_walk(.0))]
    Folder(#[source] Arc<walkdir::Error>),
    /// Any other entry that cannot be reached.
    #[error("{}", describe_walk(.0))]
    Entry(#[source] Arc<walkdir::Error>),
    /// A named pipe, device or socket named like an image: never opened (reading a named pipe
    /// would wait for a writer forever).
    #[error("not a regular file ({0}), not read")]
    NotAFile(&'static str),
}

/// Something the folder scan says that is not a failure.
#[derive(Debug, thiserror::Error)]
pub enum ScanWarning {
    /// A symbolic link back to a folder being scanned; what is behind it is scanned through its
    /// real place.
    #[error(
        "{}: symbolic link loop back to {}, not followed",
        printable(link),
        printable(ancestor)
    )]
    LinkLoop {
        /// The link.
        link: PathBuf,
        /// The folder it leads back to.
        ancestor: PathBuf,
    },
}

/// A walkdir error as [`describe_io`] words I/O errors, when it is one.
fn describe_walk(error: &walkdir::Error) -> String {
    match error.io_error() {
        Some(io_error) => describe_io(io_error),
        None => error.to_string(),
    }
}

/// The inputs of a batch, found by [`discover_inputs`].
#[derive(Debug, Default)]
pub struct Discovery {
    /// The inputs of the requested shard, sorted by relative path.
    pub inputs: Vec<Input>,
    /// Files in the folders that were left out because they have no image extension.
    pub not_images: usize,
    /// Files in the folders that were left out because they do not match the glob.
    pub excluded_by_glob: usize,
    /// Inputs that belong to other shards.
    pub in_other_shards: usize,
    /// Things worth saying that are not failures.
    pub warnings: Vec<ScanWarning>,
    /// Canonical paths of every input of every shard: no output may land on one of them.
    pub(super) protected: HashSet<PathBuf>,
    /// The outputs of the other shards' inputs, relative to the output folder: the report may
    /// not land on one of them either.
    pub(super) other_shard_outputs: Vec<PathBuf>,
}

/// Finds the inputs: files named directly are always taken; folders are scanned (recursively if
/// `options.recursive`) for files with an image extension that match `options.glob`. Symbolic
/// links are followed; a link back to a folder being scanned is reported in
/// [`Discovery::warnings`] and not followed again. The result is sorted by relative path, the same
/// file reached twice under the same relative path is kept once, and only `options.shard` is kept.
///
/// Errors: an input that does not exist or cannot be read, a bad glob, or two inputs with the same
/// output (checked across all shards, since they would share the output folder).
pub fn discover_inputs(
    inputs: &[PathBuf],
    options: &BatchOptions,
) -> Result<Discovery, BatchError> {
    let glob = options.glob.as_deref().map(compile_glob).transpose()?;
    let mut discovery = Discovery::default();
    let mut found = Vec::new();
    for input in inputs {
        let metadata = fs::metadata(input).map_err(|source| BatchError::Input {
            path: input.clone(),
            source,
        })?;
        if metadata.is_dir() {
            // Fail early on a folder we cannot list rather than report it as one bad entry.
            fs::read_dir(input).map_err(|source| BatchError::Input {
                path: input.clone(),
                source,
            })?;
            scan_folder(
                input,
                options.recursive,
                glob.as_ref(),
                &mut discovery,
                &mut found,
            );
        } else {
            let Some(name) = input.file_name() else {
                return Err(BatchError::Input {
                    path: input.clone(),
                    source: io::Error::other("not a file name"),
                });
            };
            found.push(new_input(input.clone(), PathBuf::from(name), None));
        }
    }

    found.sort_by(|a, b| (&a.relative, &a.source).cmp(&(&b.relative, &b.source)));
    // The same file reached twice (a folder and a file in it, a folder given twice) is one input.
    found.dedup_by(|later, earlier| {
        later.relative == earlier.relative
            && later.canonical.is_some()
            && later.canonical == earlier.canonical
    });

    let mut outputs: HashMap<PathBuf, &Input> = HashMap::new();
    for input in found.iter().filter(|input| input.unreadable.is_none()) {
        if let Some(first) = outputs.insert(input.output_relative(options.format), input) {
            return Err(BatchError::OutputCollision {
                output: input.output_relative(options.format),
                first: first.source.clone(),
                second: input.source.clone(),
            });
        }
    }

    discovery.protected = found
        .iter()
        .filter_map(|input| input.canonical.clone())
        .collect();
    let total = found.len();
    discovery.inputs = match options.shard {
        Some(shard) => {
            let (mine, others): (Vec<Input>, Vec<Input>) = found
                .into_iter()
                .partition(|input| shard.contains(&input.relative));
            discovery.other_shard_outputs = others
                .iter()
                .filter(|input| input.unreadable.is_none())
                .map(|input| input.output_relative(options.format))
                .collect();
            mine
        }
        None => found,
    };
    discovery.in_other_shards = total - discovery.inputs.len();
    Ok(discovery)
}

fn new_input(source: PathBuf, relative: PathBuf, unreadable: Option<Unreadable>) -> Input {
    let canonical = fs::canonicalize(&source).ok();
    Input {
        source,
        relative,
        unreadable,
        canonical,
    }
}

/// A compiled `--glob`, with the rule for what it is matched against.
struct Filter {
    matcher: GlobMatcher,
    /// The pattern has no `/`: match the file name, wherever the file is.
    file_name_only: bool,
}

impl Filter {
    fn matches(&self, relative: &Path) -> bool {
        if self.file_name_only {
            relative
                .file_name()
                .is_some_and(|name| self.matcher.is_match(name))
        } else {
            // Match with `/` separators on every platform, like the shard key.
            self.matcher
                .is_match(String::from_utf8_lossy(&shard_key(relative)).as_ref())
        }
    }
}

fn compile_glob(pattern: &str) -> Result<Filter, BatchError> {
    let glob = GlobBuilder::new(pattern)
        .literal_separator(true)
        .build()
        .map_err(|source| BatchError::Glob {
            pattern: pattern.to_string(),
            source,
        })?;
    Ok(Filter {
        matcher: glob.compile_matcher(),
        file_name_only: !pattern.contains('/'),
    })
}

/// Walks `root` (and its subfolders when `recursive`) in name order: every file that the glob and
/// the extension select goes to `found`, readable or not; `discovery` counts the others and keeps
/// the warnings.
fn scan_folder(
    root: &Path,
    recursive: bool,
    glob: Option<&Filter>,
    discovery: &mut Discovery,
    found: &mut Vec<Input>,
) {
    let walker = WalkDir::new(root)
        .follow_links(true)
        .min_depth(1)
        .max_depth(if recursive { usize::MAX } else { 1 })
        .sort_by_file_name();
    for entry in walker {
        let input = match entry {
            Ok(entry) => walked_file(&entry, root, glob, discovery),
            Err(error) => unreachable_entry(error, root, glob, discovery),
        };
        found.extend(input);
    }
}

/// Whether a file passes the glob and the extension test, counting those that do not.
fn wanted(relative: &Path, glob: Option<&Filter>, discovery: &mut Discovery) -> bool {
    if glob.is_some_and(|glob| !glob.matches(relative)) {
        discovery.excluded_by_glob += 1;
        false
    } else if !is_image_path(relative) {
        discovery.not_images += 1;
        false
    } else {
        true
    }
}

/// The input of an entry the walk reached, if it is no folder and is wanted; one that is not a
/// regular file (a named pipe, a device) is taken unreadable, to be reported.
fn walked_file(
    entry: &walkdir::DirEntry,
    root: &Path,
    glob: Option<&Filter>,
    discovery: &mut Discovery,
) -> Option<Input> {
    if entry.file_type().is_dir() {
        return None;
    }
    let relative = relative_to(entry.path(), root);
    if !wanted(&relative, glob, discovery) {
        return None;
    }
    // Links are followed: the kind is the target's.
    let not_a_file = (!entry.file_type().is_file())
        .then(|| {
            entry
                .metadata()
                .ok()
                .and_then(|metadata| not_a_file_kind(&metadata))
                .unwrap_or("not a file")
        })
        .map(Unreadable::NotAFile);
    Some(new_input(entry.path().to_path_buf(), relative, not_a_file))
}

/// The unreadable input of an entry the walk could not reach (a broken link, a folder or file it
/// may not read), or none: a link loop is a warning, the root itself was checked by the caller,
/// and a file that would not have been taken is not reported.
fn unreachable_entry(
    error: walkdir::Error,
    root: &Path,
    glob: Option<&Filter>,
    discovery: &mut Discovery,
) -> Option<Input> {
    let path = error.path().unwrap_or(root).to_path_buf();
    if let Some(ancestor) = error.loop_ancestor() {
        // Everything behind the link is scanned through its real place already.
        discovery.warnings.push(ScanWarning::LinkLoop {
            link: path,
            ancestor: ancestor.to_path_buf(),
        });
        return None;
    }
    let relative = relative_to(&path, root);
    if relative.as_os_str().is_empty() {
        return None; // the root itself, checked readable by the caller
    }
    let link_or_file = fs::symlink_metadata(&path);
    let is_folder = link_or_file.as_ref().is_ok_and(|m| m.is_dir());
    // A file we cannot reach is reported only if it would have been taken.
    if !is_folder && !wanted(&relative, glob, discovery) {
        return None;
    }
    let broken_link = error
        .io_error()
        .is_some_and(|io_error| io_error.kind() == io::ErrorKind::NotFound)
        && link_or_file.is_ok_and(|m| m.file_type().is_symlink());
    let unreadable = if broken_link {
        Unreadable::BrokenLink
    } else if is_folder && error.io_error().is_some() {
        Unreadable::Folder(Arc::new(error))
    } else {
        Unreadable::Entry(Arc::new(error))
    };
    Some(new_input(path, relative, Some(unreadable)))
}

fn relative_to(path: &Path, root: &Path) -> PathBuf {
    path.strip_prefix(root).unwrap_or(path).to_path_buf()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn image_extensions_are_recognised_in_any_case() {
        for name in [
            "a.png",
            "b.JPG",
            "c.Jpeg",
            "d.tiff",
            "e.qoi",
            "f.ff",
            "dir/g.WebP",
        ] {
            assert!(is_image_path(Path::new(name)), "{name}");
        }
        for name in ["a.svg", "b.txt", "png", "c.png.bak", ".png", "d"] {
            assert!(!is_image_path(Path::new(name)), "{name}");
        }
    }

    #[test]
    fn a_glob_without_slash_matches_file_names_anywhere() {
        let glob = compile_glob("scan-*").unwrap();
        assert!(glob.matches(Path::new("scan-1.png")));
        assert!(glob.matches(Path::new("deep/er/scan-2.png")));
        assert!(!glob.matches(Path::new("scan-dir/other.png")));
    }

    #[test]
    fn a_glob_with_slash_matches_the_relative_path() {
        let everywhere = compile_glob("**/*.png").unwrap();
        assert!(everywhere.matches(Path::new("top.png")));
        assert!(everywhere.matches(Path::new("a/b/deep.png")));
        assert!(!everywhere.matches(Path::new("a/b/deep.jpg")));
        let one_level = compile_glob("2024/*.png").unwrap();
        assert!(one_level.matches(Path::new("2024/a.png")));
        assert!(
            !one_level.matches(Path::new("2024/sub/a.png")),
            "`*` crossed a `/`"
        );
        assert!(!one_level.matches(Path::new("a.png")));
    }

    #[test]
    fn a_bad_glob_is_an_error() {
        let error = compile_glob("scan-[")
            .err()
            .expect("an unclosed class must be refused");
        assert!(
            error.to_string().starts_with("--glob \"scan-[\": "),
            "{error}"
        );
    }
}
