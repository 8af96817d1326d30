//! The track table: assignment, clusters, gates, lifecycle, capacity,
//! crossing targets and static construction.

mod assign;
mod capacity;
mod clusters;
mod crossing;
mod gate;
mod lifecycle;
mod static_construction;
mod support;
