//! The track table: assignment, clusters, gates, lifecycle, capacity,
//! displacement in a full table, crossing targets and static construction.

mod assign;
mod capacity;
mod clusters;
mod crossing;
mod displacement;
mod gate;
mod gate_kept;
mod lifecycle;
mod static_construction;
mod support;
