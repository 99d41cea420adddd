//! J1939 (SAE J1939-21) fields of a 29-bit identifier: priority (3 bits), extended data page,
//! data page, PDU format (PF), PDU specific (PS) and source address (SA). PF below
//! [`PDU2_MIN_PF`] is PDU1 (PS is a destination address), from there up PDU2 (broadcast; PS
//! is a group extension and part of the PGN).

pub use crate::constants::{GLOBAL_ADDRESS, PDU2_MIN_PF};

/// A 29-bit identifier taken apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct J1939Id {
    /// Priority, 0 (highest) to 7.
    pub priority: u8,
    /// Parameter group number (18 bits; PS included only for PDU2).
    pub pgn: u32,
    /// Source address.
    pub source_address: u8,
    /// Destination address (PDU1), or `None` for broadcast PDU2 groups.
    pub destination_address: Option<u8>,
}

impl J1939Id {
    /// Take a 29-bit identifier apart (bits above 28 are ignored).
    pub const fn from_id(id: u32) -> Self {
        Self {
            priority: priority(id),
            pgn: pgn(id),
            source_address: source_address(id),
            destination_address: destination_address(id),
        }
    }

    /// The 29-bit identifier.
    pub const fn to_id(&self) -> u32 {
        compose(
            self.priority,
            self.pgn,
            self.source_address,
            self.destination_address,
        )
    }
}

/// Priority (bits 26–28).
#[inline]
pub const fn priority(id: u32) -> u8 {
    ((id >> 26) & 0x7) as u8
}

/// PDU format (bits 16–23).
#[inline]
pub const fn pdu_format(id: u32) -> u8 {
    ((id >> 16) & 0xFF) as u8
}

/// PDU specific (bits 8–15): destination address (PDU1) or group extension (PDU2).
#[inline]
pub const fn pdu_specific(id: u32) -> u8 {
    ((id >> 8) & 0xFF) as u8
}

/// Source address (bits 0–7).
#[inline]
pub const fn source_address(id: u32) -> u8 {
    (id & 0xFF) as u8
}

/// Whether the identifier is a PDU2 (broadcast) parameter group.
#[inline]
pub const fn is_pdu2(id: u32) -> bool {
    pdu_format(id) >= PDU2_MIN_PF
}

/// Parameter group number: EDP, DP, PF and (PDU2 only) PS.
#[inline]
pub const fn pgn(id: u32) -> u32 {
    let pgn = (id >> 8) & 0x3_FFFF;
    if is_pdu2(id) {
        pgn
    } else {
        pgn & 0x3_FF00
    }
}

/// Destination address of a PDU1 identifier; `None` for PDU2.
#[inline]
pub const fn destination_address(id: u32) -> Option<u8> {
    if is_pdu2(id) {
        None
    } else {
        Some(pdu_specific(id))
    }
}

/// A 29-bit identifier from its fields. For PDU1 groups `destination` goes into PS
/// (`None`: the global address); for PDU2 it is ignored.
#[inline]
pub const fn compose(priority: u8, pgn: u32, source: u8, destination: Option<u8>) -> u32 {
    let pf = (pgn >> 8) & 0xFF;
    let mut pgn = pgn & 0x3_FFFF;
    if pf < PDU2_MIN_PF as u32 {
        let da = match destination {
            Some(da) => da,
            None => GLOBAL_ADDRESS,
        };
        pgn = (pgn & 0x3_FF00) | da as u32;
    }
    ((priority as u32 & 0x7) << 26) | (pgn << 8) | source as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decomposes_and_composes() {
        // PDU1: 0x1801B0A0 = priority 6, PF 0x01, DA 0xB0, SA 0xA0.
        let id = J1939Id::from_id(0x1801_B0A0);
        assert_eq!(
            id,
            J1939Id {
                priority: 6,
                pgn: 0x0100,
                source_address: 0xA0,
                destination_address: Some(0xB0)
            }
        );
        assert_eq!(id.to_id(), 0x1801_B0A0);
        // PDU2: 0x18FFAF00 = priority 6, PGN 0xFFAF, SA 0x00.
        let id = J1939Id::from_id(0x18FF_AF00);
        assert_eq!(
            id,
            J1939Id {
                priority: 6,
                pgn: 0xFFAF,
                source_address: 0,
                destination_address: None
            }
        );
        assert_eq!(id.to_id(), 0x18FF_AF00);
    }
}
