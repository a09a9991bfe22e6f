//! The process and its operating system: every file read or written (`files`), the memory the
//! machine has (`memory`) and the signals that stop a render (`interrupt`).
//!
//! Uses no other folder.
pub mod files;
pub mod interrupt;
pub mod memory;
