//! Errors shared by all device traits, in the style of embedded-hal: each implementation has
//! its own error type, and generic code inspects it through [`ErrorKind`].

use core::fmt;

/// What went wrong, independent of the implementation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The device gave no fresh sample within its deadline.
    Timeout,
    /// The device answered with data that failed validation (checksum, NaN, range).
    InvalidData,
    /// The device is not connected or its driver is gone.
    Disconnected,
    /// A command was refused because it lies outside the device's limits.
    OutOfRange,
    /// Anything else; see the implementation's own error for detail.
    Other,
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match self {
            Self::Timeout => "no fresh sample within the deadline",
            Self::InvalidData => "device sent invalid data",
            Self::Disconnected => "device disconnected",
            Self::OutOfRange => "command outside the device limits",
            Self::Other => "device error",
        };
        f.write_str(text)
    }
}

/// An implementation's error: anything `Debug` that can say which [`ErrorKind`] it is.
pub trait Error: fmt::Debug {
    fn kind(&self) -> ErrorKind;
}

impl Error for ErrorKind {
    fn kind(&self) -> ErrorKind {
        *self
    }
}

impl Error for core::convert::Infallible {
    fn kind(&self) -> ErrorKind {
        match *self {}
    }
}

/// Names the error type of a device implementation.
pub trait ErrorType {
    type Error: Error;
}

impl<T: ErrorType + ?Sized> ErrorType for &mut T {
    type Error = T::Error;
}
