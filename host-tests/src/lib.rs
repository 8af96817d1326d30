//! Host-side support for abtrack: what needs `std`.
