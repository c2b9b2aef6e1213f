//! The one check every output of a run goes through before anything is written (SVGs, the batch
//! report, the `--debug` pictures, `-o` of every command): an output may not be one of the run's
//! inputs, nor a file another output of the same run also writes, nor anything but a regular
//! file or nothing (a device, a named pipe or a folder is never replaced by a file).
//! Symbolic links are resolved, so a link or a second name for an input is refused too.

use std::collections::{HashMap, HashSet};
use std::fs;
use std::path::{Component, Path, PathBuf};

use super::read::not_a_file_kind;
use super::{parent_folder, printable};

/// Why an output was refused. Its text is one line for a user, without the output's name.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum OutputRefusal {
    /// The output is one of the run's inputs.
    #[error("refusing to overwrite an input")]
    Input,
    /// Another output of the same run is the same file.
    #[error("refusing to write it twice: it is also the output {}", printable(.other))]
    AlsoWritten {
        /// The other output, as it was named.
        other: PathBuf,
    },
    /// Something other than a regular file is there.
    #[error("refusing to replace {0} with a file")]
    NotAFile(&'static str),
}

/// The inputs and outputs of one run, for [`OutputPlan::claim`].
#[derive(Debug, Default)]
pub struct OutputPlan {
    /// Every input, symbolic links resolved.
    inputs: HashSet<PathBuf>,
    /// Every output claimed so far, resolved, with the name it was claimed under.
    claimed: HashMap<PathBuf, PathBuf>,
    /// Folders already resolved (outputs share a few folders).
    folders: HashMap<PathBuf, PathBuf>,
}

impl OutputPlan {
    /// A plan for a run reading `inputs` (those that do not exist are left out).
    pub fn new<'a>(inputs: impl IntoIterator<Item = &'a Path>) -> Self {
        Self::with_resolved_inputs(
            inputs
                .into_iter()
                .filter_map(|input| fs::canonicalize(input).ok())
                .collect(),
        )
    }

    /// A plan for a run whose inputs are already resolved (`fs::canonicalize`).
    pub fn with_resolved_inputs(inputs: HashSet<PathBuf>) -> Self {
        Self {
            inputs,
            ..Self::default()
        }
    }

    /// Checks `output` and, if it may be written, counts it as an output of the run.
    ///
    /// # Errors
    ///
    /// [`OutputRefusal::Input`] for one of the inputs, [`OutputRefusal::AlsoWritten`] for a file
    /// already claimed (under any name), [`OutputRefusal::NotAFile`] for a folder, device, named
    /// pipe or socket.
    pub fn claim(&mut self, output: &Path) -> Result<(), OutputRefusal> {
        check_kind(output)?;
        let resolved = self.resolve(output);
        if self.inputs.contains(&resolved) {
            return Err(OutputRefusal::Input);
        }
        match self.claimed.get(&resolved) {
            Some(other) => Err(OutputRefusal::AlsoWritten {
                other: other.clone(),
            }),
            None => {
                self.claimed.insert(resolved, output.to_path_buf());
                Ok(())
            }
        }
    }

    /// Where `path` leads once written: its folder with every link resolved, and its name, or,
    /// when the name is itself a symbolic link, the file the link leads to.
    fn resolve(&mut self, path: &Path) -> PathBuf {
        let is_link = fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink());
        if is_link {
            if let Ok(target) = fs::canonicalize(path) {
                return target;
            }
        }
        let Some(name) = path.file_name() else {
            return absolute(path);
        };
        let folder = parent_folder(path).to_path_buf();
        let resolved_folder = match self.folders.get(&folder) {
            Some(resolved) => resolved.clone(),
            None => {
                let resolved = resolve_folder(&folder);
                self.folders.insert(folder, resolved.clone());
                resolved
            }
        };
        resolved_folder.join(name)
    }
}

/// Refuses anything but a regular file or nothing at `output` (links followed).
fn check_kind(output: &Path) -> Result<(), OutputRefusal> {
    match fs::metadata(output) {
        Ok(metadata) => match not_a_file_kind(&metadata) {
            Some(kind) => Err(OutputRefusal::NotAFile(kind)),
            None => Ok(()),
        },
        Err(_) => Ok(()),
    }
}

/// A folder with every symbolic link resolved; the part that does not exist yet is appended
/// as it is (nothing there can be a link).
fn resolve_folder(folder: &Path) -> PathBuf {
    let mut existing = absolute(folder);
    let mut missing = Vec::new();
    loop {
        if let Ok(resolved) = fs::canonicalize(&existing) {
            return missing
                .into_iter()
                .rev()
                .fold(resolved, |path, name| path.join(name));
        }
        match (
            existing.file_name().map(|name| name.to_os_string()),
            existing.parent(),
        ) {
            (Some(name), Some(parent)) => {
                missing.push(name);
                existing = parent.to_path_buf();
            }
            _ => return absolute(folder),
        }
    }
}

/// `path` made absolute against the current folder, with `.` and `..` taken out lexically.
fn absolute(path: &Path) -> PathBuf {
    let joined = std::env::current_dir()
        .map(|current| current.join(path))
        .unwrap_or_else(|_| path.to_path_buf());
    let mut clean = PathBuf::new();
    for component in joined.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                clean.pop();
            }
            other => clean.push(other),
        }
    }
    clean
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_input_under_any_name_is_refused() {
        let folder = tempfile::tempdir().unwrap();
        let input = folder.path().join("in.png");
        fs::write(&input, b"png").unwrap();
        let mut plan = OutputPlan::new([input.as_path()]);
        assert_eq!(plan.claim(&input), Err(OutputRefusal::Input));
        let roundabout = folder.path().join("sub/../in.png");
        fs::create_dir(folder.path().join("sub")).unwrap();
        assert_eq!(plan.claim(&roundabout), Err(OutputRefusal::Input));
        #[cfg(unix)]
        {
            let link = folder.path().join("link.svg");
            std::os::unix::fs::symlink(&input, &link).unwrap();
            assert_eq!(plan.claim(&link), Err(OutputRefusal::Input));
            let linked_folder = folder.path().join("again");
            std::os::unix::fs::symlink(folder.path(), &linked_folder).unwrap();
            assert_eq!(
                plan.claim(&linked_folder.join("in.png")),
                Err(OutputRefusal::Input)
            );
        }
        assert_eq!(plan.claim(&folder.path().join("in.svg")), Ok(()));
    }

    #[test]
    fn two_outputs_may_not_be_one_file() {
        let folder = tempfile::tempdir().unwrap();
        let mut plan = OutputPlan::new([]);
        let report = folder.path().join("out/report.jsonl");
        assert_eq!(plan.claim(&report), Ok(()));
        assert_eq!(
            plan.claim(&report),
            Err(OutputRefusal::AlsoWritten {
                other: report.clone()
            })
        );
        fs::create_dir(folder.path().join("sub")).unwrap();
        let other_name = folder.path().join("sub/../out/report.jsonl");
        assert_eq!(
            plan.claim(&other_name),
            Err(OutputRefusal::AlsoWritten {
                other: report.clone()
            })
        );
        assert_eq!(plan.claim(&folder.path().join("out/a.svg")), Ok(()));
    }

    #[cfg(unix)]
    #[test]
    fn devices_pipes_and_folders_are_never_replaced() {
        let folder = tempfile::tempdir().unwrap();
        let mut plan = OutputPlan::new([]);
        assert_eq!(
            plan.claim(Path::new("/dev/null")),
            Err(OutputRefusal::NotAFile("a device"))
        );
        let pipe = folder.path().join("pipe.svg");
        rustix::fs::mkfifoat(
            rustix::fs::CWD,
            &pipe,
            rustix::fs::Mode::RUSR | rustix::fs::Mode::WUSR,
        )
        .unwrap();
        assert_eq!(
            plan.claim(&pipe),
            Err(OutputRefusal::NotAFile("a named pipe"))
        );
        assert_eq!(
            plan.claim(folder.path()),
            Err(OutputRefusal::NotAFile("a folder"))
        );
        assert_eq!(
            OutputRefusal::NotAFile("a named pipe").to_string(),
            "refusing to replace a named pipe with a file"
        );
    }
}
