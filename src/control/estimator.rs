//! State estimation (in progress).
