//! What a render gives: the developed image (`film`), its AOVs (`aov`), image files, comparing
//! images (`compare`) and streaming to the tev viewer (`tev`).
//!
//! Uses `backend` (the sums a film is developed from), `prepare` (a render's buffers: its size,
//! filter and AOVs), `scene`, `load` (reading EXR files) and `system`.
pub mod aov;
pub mod compare;
pub mod film;
pub mod tev;
