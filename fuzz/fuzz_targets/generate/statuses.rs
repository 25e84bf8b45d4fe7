//! The statuses: which the library defines, `tbasis_status_string` for each (and for any other
//! value), and whether the status a call returned is one its inputs allow.

use core::ffi::CStr;

use crate::codes::*;
use crate::ffi::*;
use crate::status::*;

use crate::arena::bit;

/// The statuses the inputs call for: `hard` are certain errors, `soft` are ones the header is
/// ambiguous about (the call may also succeed).
pub struct Expect {
    pub hard: u32,
    pub soft: u32,
}

/// The statuses the C library defines: every value `status.rs` describes (`message_nul`), so the
/// list grows with the library's own.
fn known_statuses() -> &'static [tbasis_status] {
    static KNOWN: std::sync::OnceLock<Vec<tbasis_status>> = std::sync::OnceLock::new();
    KNOWN.get_or_init(|| {
        let known: Vec<tbasis_status> = (0..=u8::MAX.into()).filter(|&s| message_nul(s).is_some()).collect();
        for &s in &known {
            // SAFETY: the library returns a static NUL-terminated string for every value.
            let text = unsafe { CStr::from_ptr(tbasis_status_string(s)) };
            let message = message_nul(s).unwrap();
            assert_eq!(
                text.to_bytes_with_nul(),
                message.as_bytes(),
                "tbasis_status_string({s}) is not its message"
            );
            assert!(!text.to_bytes().is_empty(), "empty status string for {s}");
        }
        known
    })
}

/// A status a call returned: one the library defines, with its string.
fn check_status_string(status: tbasis_status) {
    assert!(
        known_statuses().contains(&status),
        "status {status} is none the library defines ({:?})",
        known_statuses()
    );
    // SAFETY: the library returns a static NUL-terminated string for every value.
    let text = unsafe { CStr::from_ptr(tbasis_status_string(status)) };
    assert!(!text.to_bytes().is_empty(), "empty status string for {status}");
}

/// `status` is allowed by `expect`.
pub fn check_status(status: tbasis_status, expect: &Expect, policy: u32, what: &str) {
    check_status_string(status);
    assert_ne!(status, TBASIS_ERROR_INTERNAL, "{what}: TBASIS_ERROR_INTERNAL");
    match status {
        TBASIS_OK => assert!(
            expect.hard == 0,
            "{what}: TBASIS_OK, but the inputs call for statuses {:#x}",
            expect.hard
        ),
        TBASIS_ERROR_DEGENERATE_UV => assert!(
            expect.hard == 0 && policy == TBASIS_DEGENERATE_REJECT,
            "{what}: DEGENERATE_UV with policy {policy}, statuses due {:#x}",
            expect.hard
        ),
        e => assert!(
            e < 32 && (expect.hard | expect.soft) & bit(e) != 0,
            "{what}: status {e}, but the inputs call for {:#x} (or {:#x})",
            expect.hard,
            expect.soft
        ),
    }
}

/// `tbasis_status_string` of any value: a static non-empty string, the status's message for a
/// status the library defines and the same fallback for every other value.
pub fn check_any_status_string(value: u32) {
    // SAFETY: the library returns a static NUL-terminated string for every value.
    let text = unsafe { CStr::from_ptr(tbasis_status_string(value)) };
    assert!(!text.to_bytes().is_empty(), "empty status string for {value}");
    match message_nul(value) {
        Some(message) => assert_eq!(
            text.to_bytes_with_nul(),
            message.as_bytes(),
            "tbasis_status_string({value}) is not its message"
        ),
        None => {
            // SAFETY: as above.
            let unknown = unsafe { CStr::from_ptr(tbasis_status_string(u32::MAX)) };
            assert!(
                message_nul(u32::MAX).is_none() && text == unknown,
                "tbasis_status_string({value}), no status, is not the fallback ({unknown:?}): {text:?}"
            );
        }
    }
}
