pub mod ida;
mod linsol;
