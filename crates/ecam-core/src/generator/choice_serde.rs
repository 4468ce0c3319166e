//! How an option chosen by name or code (an acceleration curve, a
//! placement, a key point's curve) is written and read by serde: its own
//! file so that the options and [`schema`](super::schema), which lists
//! their names, do not import each other.

/// Serde for an option chosen by name or code: written as its name, read
/// from a name or a code (integer or text) through `from_name`; anything
/// else is refused with "unknown WHAT "text"; use NAMES".
macro_rules! choice_serde {
    ($ty:ty, $what:literal) => {
        impl serde::Serialize for $ty {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> serde::Deserialize<'de> for $ty {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct Visitor;
                impl serde::de::Visitor<'_> for Visitor {
                    type Value = $ty;
                    fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                        write!(f, "a {} name or code", $what)
                    }
                    fn visit_str<E: serde::de::Error>(self, text: &str) -> Result<$ty, E> {
                        <$ty>::from_name(text).ok_or_else(|| {
                            E::custom(alloc::format!(
                                "unknown {} {:?}; use {}",
                                $what,
                                text,
                                <$ty>::NAMES
                            ))
                        })
                    }
                    fn visit_i64<E: serde::de::Error>(self, code: i64) -> Result<$ty, E> {
                        self.visit_str(&alloc::format!("{code}"))
                    }
                    fn visit_u64<E: serde::de::Error>(self, code: u64) -> Result<$ty, E> {
                        self.visit_str(&alloc::format!("{code}"))
                    }
                }
                d.deserialize_any(Visitor)
            }
        }
    };
}
pub(crate) use choice_serde;
