#!/usr/bin/env bash
# A test PKI for DDS Security (PKI-DH authentication, Access-Permissions, AES-GCM-GMAC):
#   scripts/make_test_pki.sh OUT_DIR IDENTITY...
# makes in OUT_DIR a CA (ca.cert.pem, ca.key.pem: the identity and the permissions CA), the
# governance signed by it (governance.smime: only authenticated participants join, discovery,
# liveliness and every message encrypted, read and write access controlled on every topic) and,
# for each IDENTITY (a robot id, "fusion", ...), a key, a certificate signed by the CA
# (IDENTITY.key.pem, IDENTITY.cert.pem, subject CN=IDENTITY, O=mrslam, C=ES) and its signed
# permissions (IDENTITY.permissions.smime: publish and subscribe on every mrslam topic, any
# domain). Keys are ECDSA P-256. For tests and trials, not for a fleet: the CA key sits beside
# the certificates.
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 OUT_DIR IDENTITY..." >&2
  exit 2
fi
out="$1"
shift
mkdir -p "$out"
cd "$out"

quiet() { "$@" > /dev/null 2>&1 || { echo "make_test_pki: failed: $*" >&2; exit 1; }; }

if [ ! -f ca.cert.pem ]; then
  quiet openssl ecparam -name prime256v1 -genkey -noout -out ca.key.pem
  quiet openssl req -new -x509 -sha256 -key ca.key.pem -days 3650 \
    -subj "/C=ES/O=mrslam/CN=mrslam test CA" -out ca.cert.pem
fi

cat > governance.xml <<'XML'
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>0</min><max>232</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>ENCRYPT</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
XML
quiet openssl smime -sign -text -in governance.xml -out governance.smime \
  -signer ca.cert.pem -inkey ca.key.pem

for identity in "$@"; do
  case "$identity" in
    *[!A-Za-z0-9_-]*) echo "make_test_pki: '$identity' is not an identity (A-Z a-z 0-9 _ -)" >&2; exit 2 ;;
  esac
  quiet openssl ecparam -name prime256v1 -genkey -noout -out "$identity.key.pem"
  quiet openssl req -new -sha256 -key "$identity.key.pem" \
    -subj "/C=ES/O=mrslam/CN=$identity" -out "$identity.csr.pem"
  quiet openssl x509 -req -sha256 -days 3650 -in "$identity.csr.pem" -CA ca.cert.pem \
    -CAkey ca.key.pem -CAcreateserial -out "$identity.cert.pem"
  rm -f "$identity.csr.pem"
  cat > "$identity.permissions.xml" <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$identity">
      <subject_name>CN=$identity, O=mrslam, C=ES</subject_name>
      <validity>
        <not_before>2020-01-01T00:00:00</not_before>
        <not_after>2040-01-01T00:00:00</not_after>
      </validity>
      <allow_rule>
        <domains><id_range><min>0</min><max>232</max></id_range></domains>
        <publish><topics><topic>*</topic></topics></publish>
        <subscribe><topics><topic>*</topic></topics></subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
XML
  quiet openssl smime -sign -text -in "$identity.permissions.xml" \
    -out "$identity.permissions.smime" -signer ca.cert.pem -inkey ca.key.pem
done
echo "make_test_pki: CA, governance and ${#} identities in $out"
