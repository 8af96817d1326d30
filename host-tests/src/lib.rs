//! Host-side support for abtrack: what needs `std`.

pub mod reference_ra;
