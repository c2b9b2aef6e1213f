//! Shards: a fixed share of a batch's inputs, chosen by a stable hash of their relative paths, so
//! that several machines can share one batch without talking to each other.

use std::fmt;
use std::path::{Component, Path};
use std::str::FromStr;

/// Shard `index` of `count` (both counted from 1): the inputs whose relative path hashes to it.
///
/// A file belongs to shard K of N iff the FNV-1a 64-bit hash of its relative path (UTF-8 bytes,
/// `/` between components) modulo N equals K − 1. The hash is fixed, unlike `std`'s randomised
/// one, so every machine and every run agrees, and shards 1/N … N/N partition the inputs exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, from 1 to `count`.
    pub index: u64,
    /// How many shards there are, at least 1.
    pub count: u64,
}

/// Why a shard description like `2/5` was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    /// Not two whole numbers separated by `/`.
    #[error("expected K/N (shard K of N, like 2/5), found {0:?}")]
    Syntax(String),
    /// N is 0.
    #[error("the number of shards must be at least 1")]
    NoShards,
    /// K is 0 or greater than N.
    #[error("shard {index} of {count} does not exist: K must be between 1 and {count}")]
    OutOfRange {
        /// The K given.
        index: u64,
        /// The N given.
        count: u64,
    },
}

impl Shard {
    /// Shard `index` of `count`, checked: 1 ≤ `index` ≤ `count`.
    pub fn new(index: u64, count: u64) -> Result<Self, ShardError> {
        if count == 0 {
            return Err(ShardError::NoShards);
        }
        if index == 0 || index > count {
            return Err(ShardError::OutOfRange { index, count });
        }
        Ok(Self { index, count })
    }

    /// Whether the input with this relative path belongs to this shard.
    pub fn contains(&self, relative: &Path) -> bool {
        fnv1a_64(&shard_key(relative)) % self.count == self.index - 1
    }
}

impl FromStr for Shard {
    type Err = ShardError;

    fn from_str(text: &str) -> Result<Self, ShardError> {
        let syntax = || ShardError::Syntax(text.to_string());
        let (index, count) = text.split_once('/').ok_or_else(syntax)?;
        // `u64::from_str` accepts a leading `+`; a shard number is plain digits.
        let number = |part: &str| {
            if part.is_empty() || !part.bytes().all(|byte| byte.is_ascii_digit()) {
                return Err(syntax());
            }
            part.parse::<u64>().map_err(|_| syntax())
        };
        Self::new(number(index)?, number(count)?)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "{}/{}", self.index, self.count)
    }
}

/// The 64-bit FNV-1a hash of `bytes`.
pub fn fnv1a_64(bytes: &[u8]) -> u64 {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes.iter().fold(OFFSET_BASIS, |hash, &byte| {
        (hash ^ u64::from(byte)).wrapping_mul(PRIME)
    })
}

/// The bytes a relative path is hashed by: its components joined with `/` whatever the platform,
/// so that a shard holds the same files on Windows and Unix.
pub(super) fn shard_key(relative: &Path) -> Vec<u8> {
    let mut key = Vec::new();
    for component in relative.components() {
        if let Component::Normal(name) = component {
            if !key.is_empty() {
                key.push(b'/');
            }
            key.extend_from_slice(os_bytes(name).as_ref());
        }
    }
    key
}

#[cfg(unix)]
fn os_bytes(name: &std::ffi::OsStr) -> std::borrow::Cow<'_, [u8]> {
    use std::os::unix::ffi::OsStrExt;
    std::borrow::Cow::Borrowed(name.as_bytes())
}

#[cfg(not(unix))]
fn os_bytes(name: &std::ffi::OsStr) -> std::borrow::Cow<'_, [u8]> {
    match name.to_string_lossy() {
        std::borrow::Cow::Borrowed(text) => std::borrow::Cow::Borrowed(text.as_bytes()),
        std::borrow::Cow::Owned(text) => std::borrow::Cow::Owned(text.into_bytes()),
    }
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::*;

    #[test]
    fn fnv1a_64_matches_the_published_test_vectors() {
        assert_eq!(fnv1a_64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a_64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a_64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn shard_key_joins_components_with_slashes() {
        let relative: PathBuf = ["scans", "2024", "a.png"].iter().collect();
        assert_eq!(shard_key(&relative), b"scans/2024/a.png");
        assert_eq!(shard_key(Path::new("a.png")), b"a.png");
    }

    #[test]
    fn shards_parse_from_k_of_n() {
        assert_eq!("2/3".parse(), Ok(Shard { index: 2, count: 3 }));
        assert_eq!("1/1".parse(), Ok(Shard { index: 1, count: 1 }));
        assert_eq!(
            Shard::new(3, 3).map(|shard| shard.to_string()),
            Ok("3/3".into())
        );
    }

    #[test]
    fn bad_shards_are_refused_with_a_reason() {
        assert_eq!(
            "0/3".parse::<Shard>(),
            Err(ShardError::OutOfRange { index: 0, count: 3 })
        );
        assert_eq!(
            "4/3".parse::<Shard>(),
            Err(ShardError::OutOfRange { index: 4, count: 3 })
        );
        assert_eq!("1/0".parse::<Shard>(), Err(ShardError::NoShards));
        for text in [
            "", "3", "1/", "/3", "a/3", "1/2/3", " 1/3", "+1/3", "-1/3", "1.0/3",
        ] {
            assert_eq!(
                text.parse::<Shard>(),
                Err(ShardError::Syntax(text.to_string())),
                "{text:?}"
            );
        }
        let message = "5/4".parse::<Shard>().unwrap_err().to_string();
        assert!(message.contains("between 1 and 4"), "{message}");
    }

    /// Pinned values (computed apart, in Python): machines running different builds must agree.
    #[test]
    fn shard_membership_is_the_documented_hash() {
        let nested: PathBuf = ["scans", "2024", "a.png"].iter().collect();
        for (relative, count, index) in [
            (Path::new("a.png"), 3, 3),
            (Path::new("a.png"), 7, 5),
            (nested.as_path(), 3, 1),
            (nested.as_path(), 7, 2),
        ] {
            assert!(
                Shard { index, count }.contains(relative),
                "{} should be in {index}/{count}",
                relative.display()
            );
        }
    }

    #[test]
    fn every_path_is_in_exactly_one_shard() {
        for count in 1..=5 {
            for number in 0..200 {
                let relative = PathBuf::from(format!("folder/scan-{number}.png"));
                let owners = (1..=count)
                    .filter(|&index| Shard { index, count }.contains(&relative))
                    .count();
                assert_eq!(owners, 1, "{} in {count} shards", relative.display());
            }
        }
    }
}
