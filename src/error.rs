//! One error type for the whole crate, grouped by whose fault it is.

use std::fmt;
use std::path::PathBuf;

/// Where in an input a problem was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// 1-based line of a text file.
    Line(u64),
    /// 0-based byte offset into a binary file or section.
    Byte(u64),
    /// The problem concerns the input as a whole.
    Whole,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(l) => write!(f, "line {l}"),
            Location::Byte(b) => write!(f, "byte offset {b}"),
            Location::Whole => f.write_str("file"),
        }
    }
}

/// A malformed input file: which format, where, and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseError {
    /// The file, when the input came from one.
    pub file: Option<PathBuf>,
    /// The format being read, such as `"OFF"`.
    pub format: &'static str,
    /// Where the problem is.
    pub location: Location,
    /// What is wrong, in words.
    pub message: String,
}

impl ParseError {
    /// A parse error not yet tied to a file; [`Error::with_file`] adds the file name later.
    pub fn new(format: &'static str, location: Location, message: impl Into<String>) -> ParseError {
        ParseError {
            file: None,
            format,
            location,
            message: message.into(),
        }
    }
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(p) => write!(f, "{}: ", p.display())?,
            None => write!(f, "<{} input>: ", self.format)?,
        }
        write!(f, "{} {}: {}", self.format, self.location, self.message)
    }
}

/// A validity rule of `spec/FORMAT.md`, by its number: `Rule(12)` is **\[V12\]**.
///
/// Every check the container reader makes belongs to one rule, so a caller (or a test) can
/// tell which rule a damaged file breaks without reading the message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Rule(pub u8);

impl Rule {
    /// The highest rule number this reader checks.
    pub const LAST: Rule = Rule(61);

    /// Every rule this reader checks, in order.
    pub fn all() -> impl Iterator<Item = Rule> {
        (1..=Rule::LAST.0).map(Rule)
    }
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "V{}", self.0)
    }
}

/// A malformed container: the section (or `header`, `section table`), the byte offset from
/// the start of the file, the rule of `spec/FORMAT.md` it breaks, and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FormatError {
    /// The file, when known.
    pub file: Option<PathBuf>,
    /// The section's tag, or `header` / `section table` / `file`.
    pub section: String,
    /// Byte offset from the start of the file.
    pub offset: u64,
    /// The validity rule broken.
    pub rule: Rule,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(p) = &self.file {
            write!(f, "{}: ", p.display())?;
        }
        write!(
            f,
            "invalid container: {} at byte offset {}: {} [{}]",
            self.section, self.offset, self.message, self.rule
        )
    }
}

/// Every error the crate returns.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// An input file is malformed.
    #[error("{0}")]
    Parse(Box<ParseError>),
    /// The file's format could not be told from its name or content.
    #[error("{}: {reason}", path.display())]
    UnknownFormat {
        /// The file concerned.
        path: PathBuf,
        /// Why the format is unknown.
        reason: String,
    },
    /// A mesh handed to the library breaks the mesh invariants (see [`crate::Mesh::validate`]).
    #[error("invalid mesh: {0}")]
    InvalidMesh(String),
    /// A caller passed an argument out of its range (an id beyond the mesh, too few
    /// positions, ...).
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// A valid input that a representation or command cannot hold or handle (a mesh beyond
    /// a representation's id space, a container kind a command does not draw).
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// An internal invariant failed: a bug in lrmesh, never the input's fault. Please report it.
    #[error("internal error (a bug in lrmesh): {0}")]
    Internal(String),
    /// A container (`.lrm`) is malformed: which section, where, and what is wrong.
    #[error("{0}")]
    Format(Box<FormatError>),
    /// A container of a major version this reader does not know.
    #[error("unsupported container version {major}.{minor} (this reader reads major version {supported})")]
    UnsupportedVersion {
        /// The file's major version.
        major: u16,
        /// The file's minor version.
        minor: u16,
        /// The major version this reader understands.
        supported: u16,
    },
    /// A section marked required that this reader does not understand.
    #[error("unknown required section `{tag}` (section table entry {index})")]
    UnknownRequiredSection {
        /// The section's tag, escaped.
        tag: String,
        /// Its position in the section table.
        index: u32,
    },
    /// An input exceeds a configured limit (see [`crate::read::Limits`]).
    #[error("{what} is {value}, over the limit of {limit}")]
    LimitExceeded {
        /// What was too large.
        what: &'static str,
        /// Its size.
        value: u64,
        /// The limit.
        limit: u64,
    },
}

impl Error {
    /// Attaches a file name to an error that was produced from bytes alone.
    pub fn with_file(self, path: &std::path::Path) -> Error {
        match self {
            Error::Parse(mut e) => {
                e.file = Some(path.to_path_buf());
                Error::Parse(e)
            }
            Error::Format(mut e) => {
                e.file = Some(path.to_path_buf());
                Error::Format(e)
            }
            other => other,
        }
    }
}

impl From<ParseError> for Error {
    fn from(e: ParseError) -> Self {
        Error::Parse(Box::new(e))
    }
}

/// The crate's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
