//! The conformance suite's own problem generators behave.
mod common;
use common::conformance::{stream, target};

#[test]
fn stream_is_seeded() {
    assert_eq!(stream(1, 10, 2), stream(1, 10, 2));
    assert_eq!(target(&[0.0, 0.0], 1), vec![0.0]);
}
