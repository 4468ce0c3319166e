//! Modbus TCP framing (Modbus Messaging on TCP/IP Implementation Guide
//! V1.0b): a 7-byte MBAP header (transaction id, protocol id 0, length =
//! unit id + PDU, unit id) before each PDU.
//!
//! Any unit id is answered (a gateway's unit ids are not ours to check) and
//! echoed. A header with another protocol id or a length outside 2..=254 is
//! not Modbus: the server closes that connection, as the specification
//! allows for framing errors, and goes on serving others. Only the bytes
//! are here; the sockets are the binary's.

/// The header of one request frame, as far as the response needs it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MbapHeader {
    /// Transaction id, echoed in the response.
    pub transaction: u16,
    /// Unit id, echoed in the response.
    pub unit: u8,
    /// Bytes of PDU that follow the header (1..=253).
    pub pdu_len: usize,
}

impl MbapHeader {
    /// Header length on the wire.
    pub const LEN: usize = 7;
    /// Largest length field: unit id + a 253-byte PDU.
    const MAX_LENGTH: u16 = 254;

    /// Reads a request header, or `None` when it is not Modbus TCP (a
    /// protocol id other than 0, a length of 0 or 1 or over 254): close
    /// the connection.
    ///
    /// ```
    /// use ecam_serve::MbapHeader;
    /// let header = MbapHeader::parse([0x12, 0x34, 0, 0, 0, 6, 9]).unwrap();
    /// assert_eq!((header.transaction, header.unit, header.pdu_len), (0x1234, 9, 5));
    /// assert_eq!(MbapHeader::parse([0, 1, 0, 1, 0, 6, 9]), None); // protocol id 1
    /// ```
    pub fn parse(header: [u8; Self::LEN]) -> Option<Self> {
        let [t_hi, t_lo, p_hi, p_lo, l_hi, l_lo, unit] = header;
        let length = u16::from_be_bytes([l_hi, l_lo]);
        if u16::from_be_bytes([p_hi, p_lo]) != 0 || !(2..=Self::MAX_LENGTH).contains(&length) {
            return None;
        }
        Some(Self {
            transaction: u16::from_be_bytes([t_hi, t_lo]),
            unit,
            pdu_len: usize::from(length) - 1,
        })
    }

    /// The response frame carrying `pdu` (at most 253 bytes, as every
    /// [`encode_response`](crate::encode_response) output is) to this request.
    pub fn frame(&self, pdu: &[u8]) -> Vec<u8> {
        // Responses are at most 252 bytes: the length fits.
        let [len_hi, len_lo] = ((pdu.len() + 1) as u16).to_be_bytes();
        let [t_hi, t_lo] = self.transaction.to_be_bytes();
        let mut frame = Vec::with_capacity(Self::LEN + pdu.len());
        frame.extend_from_slice(&[t_hi, t_lo, 0, 0, len_hi, len_lo, self.unit]);
        frame.extend_from_slice(pdu);
        frame
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_outside_the_specification_are_not_modbus() {
        for length in [0u16, 1, 255, 0xFFFF] {
            let [hi, lo] = length.to_be_bytes();
            assert_eq!(MbapHeader::parse([0, 0, 0, 0, hi, lo, 1]), None, "{length}");
        }
        assert_eq!(
            MbapHeader::parse([0, 0, 0, 0, 0, 254, 1]).map(|h| h.pdu_len),
            Some(253)
        );
        assert_eq!(
            MbapHeader::parse([0, 0, 0, 0, 0, 2, 1]).map(|h| h.pdu_len),
            Some(1)
        );
    }

    #[test]
    fn responses_echo_transaction_and_unit() {
        let header = MbapHeader::parse([0xAB, 0xCD, 0, 0, 0, 6, 0xFF]).unwrap();
        assert_eq!(
            header.frame(&[0x83, 0x02]),
            [0xAB, 0xCD, 0, 0, 0, 3, 0xFF, 0x83, 0x02]
        );
    }
}
